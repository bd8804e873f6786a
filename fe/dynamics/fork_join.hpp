// A persistent helper thread for splitting one loop in two (DESIGN.md "Performance": use
// both cores where it pays). The explicit driver evaluates the chain ~1e5 times, each call
// ~50–100 µs of element work, so starting a thread per call (~20 µs) would eat the gain:
// the helper lives as long as its owner and, between jobs, spins briefly before it sleeps
// on an atomic wait, so posting the next job costs well under a microsecond while it is
// busy and nothing when it is idle.
#pragma once

#include <atomic>
#include <exception>
#include <thread>

namespace ringcrush::fe {

class ForkJoin {
 public:
  ForkJoin();
  ~ForkJoin();
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  // Runs job(context) on the helper thread and main_part() on the calling thread; returns
  // when both are done. An exception from either is rethrown here (the main part's first).
  template <class Main>
  void run(void (*job)(void*), void* context, Main&& main_part) {
    const unsigned ticket = post(job, context);
    std::exception_ptr main_error;
    try {
      main_part();
    } catch (...) {
      main_error = std::current_exception();
    }
    join(ticket);
    if (main_error) std::rethrow_exception(main_error);
    rethrow_helper_error();
  }

 private:
  unsigned post(void (*job)(void*), void* context);
  void join(unsigned ticket);
  void rethrow_helper_error();
  void loop();

  std::atomic<unsigned> posted_{0}, finished_{0};
  std::atomic<bool> stop_{false};
  void (*job_)(void*) = nullptr;
  void* context_ = nullptr;
  std::exception_ptr helper_error_;
  std::thread thread_;
};

}  // namespace ringcrush::fe
