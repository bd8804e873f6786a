// IDA on the components that move between events (HybridOptions::ida_reduced_state). A
// hybrid model whose events restart IDA anyway may hold some components constant between
// them (Level 3 with ring inertia: the crushes of the mechanisms not flowing and the velocity
// of a ring at rest — 28 components, 5–15 of them live). Those are taken out of IDA's vector
// at each restart and held here as parameters, so the Newton matrix IDA factorises and the
// vectors it updates have the live size only.
//
// The same steps as on the whole state: IDA's error and Newton tests take the weighted RMS
// norm sqrt(Σ (e_k w_k)² / N), and a held component contributes exactly zero there (constant
// history, zero predictor and correction), so the same sum over n live components divided by
// n instead of N would tighten every test by sqrt(N/n). The tolerances are therefore scaled
// by sqrt(N/n) (tolerance_scale()): the weights fall by that factor, the norm is the whole
// state's, and the steps are the same up to round-off.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "dae_system.hpp"
#include "hybrid_system.hpp"

namespace ringcrush::hinge {

class IdaLiveState final : public DaeSystem {
 public:
  explicit IdaLiveState(HybridSystem& system);

  // Components `live` (ascending, distinct, inside the state; empty: all) move; the others
  // are held at their values in `state` until the next call. Throws std::invalid_argument on
  // a bad list, and std::logic_error when a held component has a nonzero derivative
  // `rate` there (the model's list is wrong).
  void hold(const std::vector<std::size_t>& live, const std::vector<double>& state,
            const std::vector<double>& rate);

  std::size_t size() const override { return live_.size(); }
  void residual(double t, const double* y, const double* yp, double* r) override;
  bool has_jacobian() const override { return system_.has_jacobian(); }
  void jacobian(double t, double cj, const double* y, const double* yp, JacobianSink& jac) override;
  std::size_t root_count() const override { return system_.root_count(); }
  void roots(double t, const double* y, const double* yp, double* g) override;

  // The live components of a whole-state vector, and the whole state from live ones.
  std::vector<double> gather(const std::vector<double>& whole) const;
  std::vector<double> expand(const std::vector<double>& live) const;
  // sqrt(N/n): IDA's tolerances on the live state that keep the whole state's error norm.
  double tolerance_scale() const;
  // Set when a residual found a held component moving (IDA then stops with IDA_RES_FAIL).
  const std::string& failure() const { return failure_; }

 private:
  void scatter(const double* y, const double* yp);

  HybridSystem& system_;
  std::vector<std::size_t> live_;
  std::vector<long> where_;           // whole index → live index, −1 held
  std::vector<double> y_, yp_, r_;    // whole-state buffers: held values, live ones scattered
  std::string failure_;
};

}  // namespace ringcrush::hinge
