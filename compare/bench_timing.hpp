// Timing of benchmark runs on a shared machine (issue 8 item 6; used by `ringcrush bench`
// and `ringcrush bench-hinge`): wall time and CPU time side by side — when other jobs share
// the cores the wall time also measures the neighbours, the CPU time does not — as the
// median of repeated runs, and the machine it ran on.
#pragma once

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

namespace ringcrush::compare {

// CPU time of the calling thread / of the whole process (all threads), seconds.
double thread_cpu_s();
double process_cpu_s();

// "model name" of /proc/cpuinfo, its number of logical CPUs, and the 1-minute load average
// (−1 when unreadable).
std::string cpu_model();
int cpu_count();
double load_average();

// Median of a sample (the upper one of the middle pair); throws std::invalid_argument when empty.
double median(std::vector<double> values);

struct Timing {
  double wall_s = 0;  // median over the repeats
  double cpu_s = 0;   // median process CPU time over the repeats
  double min_wall_s = 0;
  int repeats = 0;
};

// Runs `run()` `repeats` times and returns the median times; `last` receives the result of
// the last run. Process CPU time, so that threaded runs are charged for all their threads.
// A run that costs more than `repeat_below_cpu_s` is not repeated: its time is already far
// above the timer's resolution and the scheduler's noise, and repeating it would only spend
// the benchmark's budget.
template <class Result, class Run>
Timing time_repeated(int repeats, Run&& run, Result& last, double repeat_below_cpu_s = 1e300) {
  if (repeats < 1) throw std::invalid_argument("time_repeated: repeats must be at least 1");
  std::vector<double> wall, cpu;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const double c0 = process_cpu_s();
    last = run();
    cpu.push_back(process_cpu_s() - c0);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (cpu.back() > repeat_below_cpu_s) break;
  }
  Timing t;
  t.repeats = static_cast<int>(wall.size());
  t.min_wall_s = *std::min_element(wall.begin(), wall.end());
  t.wall_s = median(wall);
  t.cpu_s = median(cpu);
  return t;
}

}  // namespace ringcrush::compare
