#include "ida_live_roots.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace ringcrush::hinge {
namespace {

int sign_of(double x) { return x > 0.0 ? 1 : x < 0.0 ? -1 : 0; }

}  // namespace

void IdaLiveRoots::select(const std::vector<std::size_t>& live, const std::vector<double>& start) {
  if (live.empty()) {
    select_all();
    return;
  }
  if (start.size() != count_)
    throw std::invalid_argument(
        fmt::format("live_roots: {} root values at the restart for {} root functions", start.size(), count_));
  for (std::size_t k = 0; k < live.size(); ++k) {
    if (live[k] >= count_)
      throw std::invalid_argument(fmt::format("live_roots: root {} outside the {} root functions", live[k], count_));
    if (k > 0 && live[k] <= live[k - 1])
      throw std::invalid_argument(
          fmt::format("live_roots: must be ascending and distinct ({} after {})", live[k], live[k - 1]));
  }
  all_ = live.size() == count_;
  live_ = live;
  held_.clear();
  held_sign_.clear();
  std::size_t next = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    if (next < live_.size() && live_[next] == i) {
      ++next;
      continue;
    }
    held_.push_back(i);
    held_sign_.push_back(sign_of(start[i]));
  }
}

void IdaLiveRoots::select_all() {
  all_ = true;
  live_.clear();
  held_.clear();
  held_sign_.clear();
}

void IdaLiveRoots::check_held(double t, const double* g) const {
  for (std::size_t k = 0; k < held_.size(); ++k)
    if (sign_of(g[held_[k]]) != held_sign_[k])
      throw std::logic_error(fmt::format(
          "live_roots: root {} is held but changed sign (sign {} at the restart, {:g} at t = {:.12g} s); the "
          "model's list misses it",
          held_[k], held_sign_[k], g[held_[k]], t));
}

void IdaLiveRoots::gather(const double* g, double* ida) const {
  if (all_) {
    for (std::size_t i = 0; i < count_; ++i) ida[i] = g[i];
    return;
  }
  for (std::size_t k = 0; k < live_.size(); ++k) ida[k] = g[live_[k]];
}

std::vector<int> IdaLiveRoots::expand(const std::vector<int>& ida_found) const {
  if (all_) return ida_found;
  std::vector<int> found(count_, 0);
  for (std::size_t k = 0; k < live_.size() && k < ida_found.size(); ++k) found[live_[k]] = ida_found[k];
  return found;
}

}  // namespace ringcrush::hinge
