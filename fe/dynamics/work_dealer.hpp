// Dealing the items of one loop (the elements of an explicit step) to the threads of a
// ForkJoin in small chunks from a shared counter, with a barrier at which every thread waits
// until all chunks are done (DESIGN.md "Performance"; issue 4: use both cores where it pays).
//
// Why not a fixed split: the calling thread also does the contact search, whose share of an
// explicit step grows from ≈ 8 % at first impact to ≈ 25 % late in the crush of the thesis
// chain (README "Performance"), so any fixed share of elements leaves one thread idle for part
// of the run. Dealt chunks balance by themselves. Which thread computes an item must not
// change a result: the items are computed into their own slots and summed afterwards in a
// fixed order (ChainModel), so the outcome does not depend on the dealing.
#pragma once

#include <algorithm>
#include <atomic>

#include "fe/dynamics/spin_wait.hpp"

namespace ringcrush::fe {

class WorkDealer {
 public:
  // Before the threads start: `count` items [0, count), dealt `chunk` at a time.
  void reset(int count, int chunk) {
    count_ = count;
    chunk_ = std::max(1, chunk);
    next_.store(0, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    failed_.store(false, std::memory_order_relaxed);
  }
  // The next chunk [begin, end); false when none is left or a thread has failed.
  bool next(int& begin, int& end) {
    if (failed_.load(std::memory_order_relaxed)) return false;
    begin = next_.fetch_add(chunk_, std::memory_order_relaxed);
    if (begin >= count_) return false;
    end = std::min(count_, begin + chunk_);
    return true;
  }
  // n items finished: their results are visible to whoever returns from wait_all().
  void done(int n) { done_.fetch_add(n, std::memory_order_release); }
  // A thread threw: the others stop taking chunks and their wait_all() returns false.
  void fail() { failed_.store(true, std::memory_order_release); }
  // Spins until every item is done (true) or a thread has failed (false). The wait is the
  // length of one chunk at most: both threads deal until nothing is left.
  bool wait_all() const {
    for (unsigned turn = 0;;) {
      if (done_.load(std::memory_order_acquire) >= count_) return true;
      if (failed_.load(std::memory_order_acquire)) return false;
      spin_wait_turn(turn);
    }
  }

 private:
  std::atomic<int> next_{0}, done_{0};
  std::atomic<bool> failed_{false};
  int count_ = 0, chunk_ = 1;
};

}  // namespace ringcrush::fe
