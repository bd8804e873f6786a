// The two-ended work dealer (fe/dynamics/work_dealer.hpp) and the chain's element pass that
// uses it (ChainModel, two threads: the caller from the front, the helper from the back):
//  - every chunk is taken exactly once, with the fixed boundaries, however the two ends race;
//    the front's chunks come in ascending order, the back's in descending order, and the two
//    meet: everything the front took lies before everything the back took;
//  - a failed thread stops the dealing;
//  - the chain's force-only pass on two threads is bitwise the one-thread pass when the
//    element count is not a multiple of the chunk (a short last chunk, taken first by the
//    back) and the fixed halves of the sums do not fall on a chunk boundary.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <thread>
#include <vector>

#include "fe/chain/chain_model.hpp"
#include "fe/dynamics/work_dealer.hpp"
#include "threaded_chain_pass.hpp"

using namespace ringcrush::fe;

TEST(WorkDealer, TwoEndsTakeEveryChunkOnceWithFixedBoundaries) {
  WorkDealer d;
  d.reset(10, 4);  // chunks [0, 4), [4, 8), [8, 10)
  int b = -1, e = -1;
  ASSERT_TRUE(d.next_back(b, e));
  EXPECT_EQ(b, 8);
  EXPECT_EQ(e, 10);
  ASSERT_TRUE(d.next(b, e));
  EXPECT_EQ(b, 0);
  EXPECT_EQ(e, 4);
  ASSERT_TRUE(d.next_back(b, e));
  EXPECT_EQ(b, 4);
  EXPECT_EQ(e, 8);
  EXPECT_FALSE(d.next(b, e));
  EXPECT_FALSE(d.next_back(b, e));
  // Nothing to deal: neither end gets a chunk, and nothing is awaited.
  d.reset(0, 4);
  EXPECT_FALSE(d.next(b, e));
  EXPECT_FALSE(d.next_back(b, e));
  EXPECT_TRUE(d.wait_all());
  // A failed thread stops the dealing: no more chunks, and wait_all() reports it.
  d.reset(12, 4);
  ASSERT_TRUE(d.next(b, e));
  d.fail();
  EXPECT_FALSE(d.next(b, e));
  EXPECT_FALSE(d.next_back(b, e));
  EXPECT_FALSE(d.wait_all());
}

TEST(WorkDealer, TwoThreadsRacingFromBothEndsMeetOnce) {
  constexpr int kCount = 1003, kChunk = 4;  // 251 chunks, the last one short
  WorkDealer d;
  for (int round = 0; round < 200; ++round) {
    d.reset(kCount, kChunk);
    std::vector<int> front, back, hits(kCount, 0);
    auto take = [&](bool from_back, std::vector<int>& got) {
      int b = 0, e = 0;
      while (from_back ? d.next_back(b, e) : d.next(b, e)) {
        EXPECT_EQ(b % kChunk, 0);
        EXPECT_EQ(e, std::min(kCount, b + kChunk));
        got.push_back(b);
        for (int i = b; i < e; ++i) ++hits[static_cast<std::size_t>(i)];
        d.done(e - b);
      }
    };
    std::thread helper(take, true, std::ref(back));
    take(false, front);
    helper.join();
    ASSERT_TRUE(d.wait_all());
    for (int i = 0; i < kCount; ++i) ASSERT_EQ(hits[static_cast<std::size_t>(i)], 1) << "item " << i << ", round " << round;
    EXPECT_TRUE(std::is_sorted(front.begin(), front.end()));
    EXPECT_TRUE(std::is_sorted(back.rbegin(), back.rend()));
    if (!front.empty() && !back.empty()) {
      EXPECT_LT(front.back(), back.back()) << "round " << round;
    }
  }
}

// 3 half rings of 6 elements: 18 elements, chunks of one lane group — 4 (the last one 2
// elements), or 8 with AVX-512 (the last one 2) — the sums' halves [0, 8) and [8, 18); bulk
// viscosity on, three committed increments.
TEST(WorkDealer, ChainPassFromBothEndsIsTheOneThreadPass) {
  for (Integration rule : {Integration::Reduced, Integration::Selective}) {
    ChainInput in;
    in.rings = 3;
    in.mesh.elements_around = 6;
    in.joints = JointKind::Free;
    in.integration = rule;
    in.bulk_viscosity = 0.06;
    test_support::ThreadedChainPass pass(in);
    ASSERT_EQ(pass.serial.mesh().elements.size(), 18u);
    pass.run(3, 21);
  }
}

// 30 elements, so that the lane groups of the two passes differ: one thread sums [0, 13) as
// 8 + 4 + 1 (AVX-512; else 4 + 4 + 4 + 1) and [13, 30) as 8 + 8 + 1; two threads deal chunks
// [0, 8), [8, 16), [16, 24), [24, 30), the last one a group of four and two elements alone.
// Every arrangement of groups of eight, four and one gives the same bits (cps8_force_lanes.hpp).
TEST(WorkDealer, LaneGroupsOfEightFourAndOneAreTheOneThreadPass) {
  ChainInput in;
  in.rings = 3;
  in.mesh.elements_around = 10;
  in.joints = JointKind::Free;
  in.integration = Integration::Selective;
  in.bulk_viscosity = 0.06;
  test_support::ThreadedChainPass pass(in);
  ASSERT_EQ(pass.serial.mesh().elements.size(), 30u);
  pass.run(3, 23);
}
