#include "fe/dynamics/fork_join.hpp"

#include "fe/dynamics/spin_wait.hpp"

namespace ringcrush::fe {

namespace {
// Spin iterations before sleeping: a few tens of µs, longer than the gap between two
// evaluations of an explicit step, much shorter than any idle period.
constexpr int kSpin = 20000;
}  // namespace

ForkJoin::ForkJoin() : thread_([this] { loop(); }) {}

ForkJoin::~ForkJoin() {
  stop_.store(true, std::memory_order_release);
  posted_.fetch_add(1, std::memory_order_acq_rel);
  posted_.notify_one();
  thread_.join();
}

unsigned ForkJoin::post(void (*job)(void*), void* context) {
  job_ = job;
  context_ = context;
  const unsigned ticket = posted_.fetch_add(1, std::memory_order_acq_rel) + 1;
  posted_.notify_one();
  return ticket;
}

void ForkJoin::join(unsigned ticket) {
  unsigned turn = 0;
  for (int i = 0; i < kSpin; ++i) {
    if (finished_.load(std::memory_order_acquire) == ticket) return;
    spin_wait_turn(turn);
  }
  for (;;) {
    const unsigned seen = finished_.load(std::memory_order_acquire);
    if (seen == ticket) return;
    finished_.wait(seen, std::memory_order_acquire);
  }
}

void ForkJoin::rethrow_helper_error() {
  if (!helper_error_) return;
  std::exception_ptr e = helper_error_;
  helper_error_ = nullptr;
  std::rethrow_exception(e);
}

void ForkJoin::loop() {
  unsigned done = 0;
  for (;;) {
    unsigned ticket = posted_.load(std::memory_order_acquire);
    unsigned turn = 0;
    for (int i = 0; i < kSpin && ticket == done; ++i) {
      spin_wait_turn(turn);
      ticket = posted_.load(std::memory_order_acquire);
    }
    if (ticket == done) {
      posted_.wait(done, std::memory_order_acquire);
      continue;
    }
    if (stop_.load(std::memory_order_acquire)) return;
    try {
      job_(context_);
    } catch (...) {
      helper_error_ = std::current_exception();
    }
    done = ticket;
    finished_.store(ticket, std::memory_order_release);
    finished_.notify_one();
  }
}

}  // namespace ringcrush::fe
