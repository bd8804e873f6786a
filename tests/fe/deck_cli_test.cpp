// `ringcrush check-deck` end to end: the corrected thesis decks read and summarise; the
// original dynamic deck is refused with "FILE:212: ..." and exit status 2.
#include <gtest/gtest.h>

#include "command_run.hpp"
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace {
using cli_testing::CommandRun;
using cli_testing::ringcrush;

const std::string thesis = std::string(RINGCRUSH_SOURCE_DIR) + "/data/thesis/";
}  // namespace

TEST(CheckDeckCli, SummarisesTheCorrectedDecks) {
  const CommandRun r = ringcrush("check-deck " + thesis + "thesis_static.inp " + thesis + "thesis_dynamic.inp");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("nodes: 332"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nodes: 2912"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rings: 6 (half model)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ignored"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mapped to history.csv"), std::string::npos) << r.output;
}

TEST(CheckDeckCli, OriginalDynamicDeckFailsAtItsLine) {
  const CommandRun r = ringcrush("check-deck " + thesis + "original/thesis_dynamic.inp");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("thesis_dynamic.inp:212: *BOUNDARY: unknown boundary type 'XYMM'"), std::string::npos)
      << r.output;
}

TEST(CheckDeckCli, SceneOptionPrintsAValidScene) {
  const CommandRun r = ringcrush("check-deck --scene " + thesis + "thesis_static.inp");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("crush_m = 0.046"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("elements_around = 22"), std::string::npos) << r.output;
}
