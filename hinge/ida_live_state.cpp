#include "ida_live_state.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace ringcrush::hinge {
namespace {

// The model's Jacobian in whole-state indices, written into IDA's live-size matrix. Entries
// in a held row or column are dropped: a held row is cj on its diagonal only (F_k = y′_k),
// and a live row depends on a held column only through a constant.
class LiveSink final : public JacobianSink {
 public:
  LiveSink(JacobianSink& out, const std::vector<long>& where) : out_(out), where_(where) {}
  void set(std::size_t row, std::size_t col, double value) override {
    const long r = where_[row], c = where_[col];
    if (r >= 0 && c >= 0) out_.set(static_cast<std::size_t>(r), static_cast<std::size_t>(c), value);
  }

 private:
  JacobianSink& out_;
  const std::vector<long>& where_;
};

}  // namespace

IdaLiveState::IdaLiveState(HybridSystem& system)
    : system_(system), y_(system.size(), 0.0), yp_(system.size(), 0.0), r_(system.size(), 0.0) {}

void IdaLiveState::hold(const std::vector<std::size_t>& live, const std::vector<double>& state,
                        const std::vector<double>& rate) {
  const std::size_t n = system_.size();
  if (state.size() != n || rate.size() != n)
    throw std::invalid_argument("IdaLiveState::hold: state and rate must match the system size");
  where_.assign(n, -1);
  live_.clear();
  if (live.empty()) {
    for (std::size_t k = 0; k < n; ++k) live_.push_back(k);
  } else {
    for (std::size_t k = 0; k < live.size(); ++k) {
      if (live[k] >= n)
        throw std::invalid_argument(
            fmt::format("live_components: component {} outside the state of {} components", live[k], n));
      if (k > 0 && live[k] <= live[k - 1])
        throw std::invalid_argument(fmt::format(
            "live_components: must be ascending and distinct ({} after {})", live[k], live[k - 1]));
    }
    live_ = live;
  }
  for (std::size_t k = 0; k < live_.size(); ++k) where_[live_[k]] = static_cast<long>(k);
  for (std::size_t k = 0; k < n; ++k)
    if (where_[k] < 0 && rate[k] != 0.0)
      throw std::logic_error(fmt::format(
          "live_components: component {} is held but moves (rate {:g}); the model's list misses it", k, rate[k]));
  y_ = state;
  std::fill(yp_.begin(), yp_.end(), 0.0);
  failure_.clear();
}

void IdaLiveState::scatter(const double* y, const double* yp) {
  for (std::size_t k = 0; k < live_.size(); ++k) {
    y_[live_[k]] = y[k];
    yp_[live_[k]] = yp[k];
  }
}

void IdaLiveState::residual(double t, const double* y, const double* yp, double* r) {
  scatter(y, yp);
  system_.residual(t, y_.data(), yp_.data(), r_.data());
  for (std::size_t k = 0; k < live_.size(); ++k) r[k] = r_[live_[k]];
  // A held component must stay put: F_k(y, y′_k = 0) = 0. Otherwise the model's list of live
  // components is wrong inside a segment, where hold()'s check at the restart cannot see it.
  for (std::size_t k = 0; k < where_.size(); ++k)
    if (where_[k] < 0 && r_[k] != 0.0) {
      failure_ = fmt::format("live_components: component {} is held but its residual is {:g} at t = {:.9g} s",
                             k, r_[k], t);
      throw std::logic_error(failure_);
    }
}

void IdaLiveState::jacobian(double t, double cj, const double* y, const double* yp, JacobianSink& jac) {
  scatter(y, yp);
  LiveSink sink(jac, where_);
  system_.jacobian(t, cj, y_.data(), yp_.data(), sink);
}

void IdaLiveState::roots(double t, const double* y, const double* yp, double* g) {
  scatter(y, yp);
  system_.roots(t, y_.data(), yp_.data(), g);
}

std::vector<double> IdaLiveState::gather(const std::vector<double>& whole) const {
  std::vector<double> out(live_.size());
  for (std::size_t k = 0; k < live_.size(); ++k) out[k] = whole[live_[k]];
  return out;
}

std::vector<double> IdaLiveState::expand(const std::vector<double>& live) const {
  std::vector<double> out = y_;  // the held values (the live ones overwritten below)
  for (std::size_t k = 0; k < live_.size(); ++k) out[live_[k]] = live[k];
  return out;
}

double IdaLiveState::tolerance_scale() const {
  return std::sqrt(static_cast<double>(system_.size()) / static_cast<double>(live_.size()));
}

}  // namespace ringcrush::hinge
