// Keyword semantics of the ABAQUS 4.8 reader on small decks whose result is known by hand
// (issue 5 item 1): case-insensitive names, comments, keyword continuation lines, NGEN,
// ELGEN with two rows, NCOPY with a rotation, ELCOPY with REFLECT, *ELSET GENERATE, symbolic
// boundaries, and output requests mapped or ignored.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "fe/deck/deck_reader.hpp"

namespace fd = ringcrush::fe::deck;

namespace {
std::string read(const std::string& name) {
  std::ifstream in(std::string(RINGCRUSH_SOURCE_DIR) + "/data/thesis/" + name);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(DeckKeywords, CaseCommentsBlankLinesAndCrLfDoNotMatter) {
  std::string lower = read("thesis_static.inp");
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::string noisy;
  std::istringstream in(lower);
  for (std::string l; std::getline(in, l);) noisy += "** comment\n  " + l + "  \r\n\n";
  const fd::DeckModel a = fd::read_deck(read("thesis_static.inp"));
  const fd::DeckModel b = fd::read_deck(noisy);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (const auto& [label, n] : a.nodes) EXPECT_EQ(b.nodes.at(label).x, n.x);
  EXPECT_EQ(a.elements.size(), b.elements.size());
  EXPECT_EQ(b.nsets.at("XSIM").labels, a.nsets.at("XSIM").labels);
}

TEST(DeckKeywords, KeywordLineContinuesAfterATrailingComma) {
  const fd::DeckModel m = fd::read_deck(
      "*NODE,\n  NSET=A\n1,0.,0.\n2,1.,0.\n*NCOPY,CHANGE NUMBER=10,\n OLD SET=A,\n SHIFT\n0.,2.,0.\n");
  EXPECT_EQ(m.nsets.at("A").labels.size(), 2u);
  EXPECT_EQ(m.nodes.at(12).x[1], 2.0);
}

TEST(DeckKeywords, NgenStraightAndNcopyRotation) {
  const fd::DeckModel m = fd::read_deck(
      "*NODE\n1,0.,0.\n5,4.,2.\n*NGEN,NSET=L\n1,5,1\n"
      // Shift by (1, 0), then turn 90° about the z axis through the origin.
      "*NCOPY,CHANGE NUMBER=100,OLD SET=L,NEW SET=C,SHIFT\n1.,0.,0.\n0.,0.,0.,0.,0.,1.,90.\n");
  EXPECT_DOUBLE_EQ(m.nodes.at(3).x[0], 2.0);  // midway
  EXPECT_DOUBLE_EQ(m.nodes.at(3).x[1], 1.0);
  // Node 5 (4, 2) → shifted (5, 2) → rotated (−2, 5).
  EXPECT_NEAR(m.nodes.at(105).x[0], -2.0, 1e-15);
  EXPECT_NEAR(m.nodes.at(105).x[1], 5.0, 1e-15);
  EXPECT_EQ(m.nsets.at("C").labels, (std::vector<int>{101, 102, 103, 104, 105}));
}

TEST(DeckKeywords, ElgenTwoRowsAndElsetGenerate) {
  // A 3 × 2 grid of MASS elements: 3 along (node +1, element +1), 2 rows (node +10, element +100).
  std::string deck = "*NODE\n";
  for (int r = 0; r < 2; ++r)
    for (int c = 1; c <= 3; ++c) deck += std::to_string(10 * r + c) + "," + std::to_string(c) + "," + std::to_string(r) + "\n";
  deck += "*ELEMENT,TYPE=MASS\n1,1\n*ELGEN,ELSET=G\n1,3,1,1,2,10,100\n*ELSET,ELSET=ROW2,GENERATE\n101,103,1\n";
  const fd::DeckModel m = fd::read_deck(deck);
  EXPECT_EQ(m.elsets.at("G").labels, (std::vector<int>{1, 2, 3, 101, 102, 103}));
  EXPECT_EQ(m.elements.at(103).nodes, std::vector<int>{13});
  EXPECT_EQ(m.elsets.at("ROW2").labels.size(), 3u);
}

TEST(DeckKeywords, Irs22ReferenceNodeIsNotIncremented) {
  const fd::DeckModel m = fd::read_deck(
      "*NODE\n1,0.,0.\n2,1.,0.\n3,2.,0.\n4,3.,0.\n5,4.,0.\n9,0.,1.\n*ELEMENT,TYPE=IRS22,ELSET=P\n1,1,2,3,9\n"
      "*ELGEN,ELSET=P\n1,2,2,1\n");
  EXPECT_EQ(m.elements.at(2).nodes, (std::vector<int>{3, 4, 5, 9}));
}

TEST(DeckKeywords, SymbolicBoundariesExpandToDofs) {
  const fd::DeckModel m = fd::read_deck("*NODE,NSET=S\n1,0.,0.\n2,0.,1.\n*BOUNDARY\nS,XSYMM\n2,ENCASTRE\n1,2,,-0.5\n");
  // XSYMM on 2 nodes: (1,1) and (5,6) each; ENCASTRE (1..6); a prescribed u2 = −0.5.
  ASSERT_EQ(m.boundaries.size(), 6u);
  EXPECT_EQ(m.boundaries[0].first_dof, 1);
  EXPECT_EQ(m.boundaries[0].last_dof, 1);
  EXPECT_EQ(m.boundaries[4].written, "ENCASTRE");
  EXPECT_EQ(m.boundaries[5].value, -0.5);
}

TEST(DeckKeywords, OutputRequestsAreMappedOrIgnoredWithAReason) {
  const fd::DeckModel m = fd::read_deck(
      "*NODE\n1,0.,0.\n*RESTART,WRITE,FREQ=25\n*STEP\n*STATIC\n1.,1.\n*NODE PRINT,FREQ=5\nU\nRF\n"
      "*EL FILE\nS\n*MONITOR,NODE=1,DOF=2\n*END STEP\n");
  ASSERT_EQ(m.outputs.size(), 1u);
  EXPECT_TRUE(m.outputs[0].mapped_to.empty());
  EXPECT_FALSE(m.outputs[0].reason.empty());
  const auto& o = m.steps.at(0).outputs;
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o[0].mapped_to, "history.csv");
  EXPECT_EQ(o[0].variables, (std::vector<std::string>{"U", "RF"}));
  EXPECT_EQ(o[1].mapped_to, "frames/*.vtu");
  EXPECT_EQ(o[2].mapped_to, "history.csv");
}

TEST(DeckKeywords, EverySupportedKeywordIsListed) {
  const auto& k = fd::supported_keywords();
  for (const char* name : {"NGEN", "NCOPY", "ELCOPY", "SLIDE LINE", "CONTROL INTERFACES", "SURFACE CONTACT", "EL FILE"})
    EXPECT_NE(std::find(k.begin(), k.end(), name), k.end()) << name;
}
