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
//
// Two ends: a thread may take its chunks from the front (next) or from the back (next_back).
// With the caller at the front and the helper at the back, each thread computes nearly the
// same items every step — they meet where the step's balance puts them, which moves by a
// chunk or two — so an item's state stays in the cache of the core that computes it, and each
// fixed half of the sums reads mostly its own thread's slots. (With one front counter the
// helper computed the first elements while the caller searched the contact, so the caller's
// half of the sums read the helper's slots and the meeting point moved from step to step; on
// a VM whose cores exchange cache lines slowly that cost a third of the two-thread step,
// README "FE dynamics", session 12.) Which thread takes a chunk still changes no result.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>

#include "fe/dynamics/spin_wait.hpp"

namespace ringcrush::fe {

class WorkDealer {
 public:
  // Before the threads start: `count` items [0, count), dealt `chunk` at a time.
  void reset(int count, int chunk) {
    count_ = std::max(0, count);
    chunk_ = std::max(1, chunk);
    const auto chunks = static_cast<std::uint64_t>((count_ + chunk_ - 1) / chunk_);
    ends_.store(chunks << 32, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    failed_.store(false, std::memory_order_relaxed);
  }
  // The next chunk [begin, end) from the front; false when none is left or a thread has
  // failed. Chunk k is always [k·chunk, min(count, (k + 1)·chunk)), from either end.
  bool next(int& begin, int& end) { return take(false, begin, end); }
  // The same from the back.
  bool next_back(int& begin, int& end) { return take(true, begin, end); }
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
  // The chunks not yet taken, [front, back): front in the low 32 bits, back in the high ones,
  // one word so that the two ends never take the same chunk.
  bool take(bool back, int& begin, int& end) {
    if (failed_.load(std::memory_order_relaxed)) return false;
    std::uint64_t ends = ends_.load(std::memory_order_relaxed);
    std::uint64_t chunk_index = 0;
    for (;;) {
      const std::uint64_t front = ends & 0xffffffffu, rear = ends >> 32;
      if (front >= rear) return false;
      chunk_index = back ? rear - 1 : front;
      const std::uint64_t taken = back ? ends - (std::uint64_t{1} << 32) : ends + 1;
      if (ends_.compare_exchange_weak(ends, taken, std::memory_order_relaxed)) break;
    }
    begin = static_cast<int>(chunk_index) * chunk_;
    end = std::min(count_, begin + chunk_);
    return true;
  }

  std::atomic<std::uint64_t> ends_{0};
  std::atomic<int> done_{0};
  std::atomic<bool> failed_{false};
  int count_ = 0, chunk_ = 1;
};

}  // namespace ringcrush::fe
