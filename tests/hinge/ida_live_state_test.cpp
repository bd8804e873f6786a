// IDA on the live components only (hinge/ida_live_state.hpp, HybridOptions::ida_reduced_state)
// and with absolute tolerances per component (HybridOptions::ida_component_tolerances): on a
// toy hybrid model with a closed form, the reduced run equals the whole-state run and the held
// components keep their values exactly; a wrong list of live components, a system with
// algebraic components, or a wrong list of tolerance scales is a named error.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "hinge/hybrid_system.hpp"

using namespace ringcrush::hinge;

namespace {

// Two counters take turns: in mode k, y_k′ = 1 + y_k (from 0: y_k = e^t − 1) and the other is
// held; y_2′ = y_k accumulates. At y_k = 1 (t = ln 2 after the switch) the mode passes to the
// other counter, which restarts from 0; the third switch stops the run.
class TakingTurns final : public HybridSystem {
 public:
  std::vector<std::size_t> live{0, 2};  // what live_components() reports in mode 0
  bool misreport = false;               // report the list for mode 0 in every mode
  bool drift = false;                   // the held counter creeps after t = 0.5 (a model bug)
  std::vector<double> atol_scale;       // absolute_tolerances(): these times the absolute
  std::size_t size() const override { return 3; }
  std::size_t root_count() const override { return 1; }
  void rhs(double t, const double* y, double* f) override {
    f[mode_] = 1.0 + y[mode_];
    f[1 - mode_] = drift && t > 0.5 ? 1e-3 : 0.0;
    f[2] = y[mode_];
  }
  void residual(double t, const double* y, const double* yp, double* r) override {
    rhs(t, y, r);
    for (int k = 0; k < 3; ++k) r[k] = yp[k] - r[k];
  }
  void event_roots(double, const double* y, double* g) override { g[0] = y[mode_] - 1.0; }
  EventAction on_event(double, std::vector<double>& y, const std::vector<int>&) override {
    if (++switches_ == 3) return EventAction::Stop;
    mode_ = 1 - mode_;
    y[static_cast<std::size_t>(mode_)] = 0.0;
    return EventAction::Continue;
  }
  std::vector<std::size_t> live_components() const override {
    if (misreport || mode_ == 0) return live;
    return {1, 2};
  }
  std::vector<double> absolute_tolerances(double, double absolute) const override {
    std::vector<double> a = atol_scale;
    for (double& x : a) x *= absolute;
    return a;
  }

 private:
  int mode_ = 0, switches_ = 0;
};

HybridOptions ida_options(bool reduced, bool component_tolerances = false) {
  HybridOptions o;
  o.integrator = HybridIntegrator::Ida;
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  o.end_time = 10.0;
  o.ida_reduced_state = reduced;
  o.ida_component_tolerances = component_tolerances;
  return o;
}

template <typename Error>
std::string error_of(TakingTurns& m, bool reduced = true, bool component_tolerances = false) {
  std::vector<double> y{0.0, 0.0, 0.0};
  try {
    run_hybrid(m, 0.0, y, ida_options(reduced, component_tolerances), {});
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

// Closed form: each segment lasts ln 2 and adds ∫ (e^t − 1) dt = 1 − ln 2 to y_2; the run stops
// at the third switch, t = 3 ln 2, with y_0 = 1 (its second segment), y_1 = 1, y_2 = 3(1 − ln 2).
TEST(IdaLiveState, ReducedRunEqualsTheWholeStateAndTheClosedForm) {
  const double ln2 = std::log(2.0);
  std::vector<double> whole{0.0, 0.0, 0.0}, reduced = whole;
  TakingTurns a, b;
  const auto wa = run_hybrid(a, 0.0, whole, ida_options(false), {});
  std::vector<double> held_values;
  const auto rb = run_hybrid(b, 0.0, reduced, ida_options(true), [&](double t, const std::vector<double>& y) {
    if (t > 0.1 && t < ln2 - 0.1) held_values.push_back(y[1]);  // counter 1 held at 0 in the first segment
  });
  EXPECT_NEAR(rb.end_time, 3.0 * ln2, 1e-8);
  for (int k : {0, 1}) EXPECT_NEAR(reduced[k], 1.0, 1e-8) << k;
  EXPECT_NEAR(reduced[2], 3.0 * (1.0 - ln2), 1e-8);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(reduced[k], whole[k], 1e-9) << k;
  EXPECT_NEAR(rb.end_time, wa.end_time, 1e-9);
  EXPECT_EQ(rb.statistics.events, wa.statistics.events);
  EXPECT_EQ(rb.statistics.restarts, wa.statistics.restarts);
  ASSERT_FALSE(held_values.empty());
  for (double v : held_values) EXPECT_EQ(v, 0.0);  // held exactly, not integrated
}

TEST(IdaLiveState, BadLiveListsAreNamedErrors) {
  TakingTurns unsorted;
  unsorted.live = {2, 0};
  EXPECT_NE(error_of<std::invalid_argument>(unsorted).find("ascending and distinct"), std::string::npos);
  TakingTurns outside;
  outside.live = {0, 2, 3};
  EXPECT_NE(error_of<std::invalid_argument>(outside).find("component 3 outside the state of 3"), std::string::npos);
  // Mode 1 reported as mode 0: counter 1 moves but is held (found at the restart).
  TakingTurns wrong;
  wrong.misreport = true;
  EXPECT_NE(error_of<std::logic_error>(wrong).find("component 1 is held but moves"), std::string::npos);
  // Counter 1 starts to creep inside the first segment: found by the residual, not at a restart.
  TakingTurns creeping;
  creeping.drift = true;
  EXPECT_NE(error_of<std::logic_error>(creeping).find("component 1 is held but its residual"), std::string::npos);
  // The whole-state path does not read the list.
  TakingTurns ignored;
  ignored.live = {2, 0};
  EXPECT_EQ(error_of<std::exception>(ignored, false), "no error");
}

// IDACalcIC works on the whole state: a system with algebraic components is refused.
TEST(IdaLiveState, AlgebraicComponentsAreRefused) {
  class WithMultiplier final : public HybridSystem {
   public:
    std::size_t size() const override { return 2; }
    std::size_t root_count() const override { return 1; }
    std::vector<double> differential_mask() const override { return {1.0, 0.0}; }
    void rhs(double, const double* y, double* f) override {
      f[0] = 1.0;
      f[1] = 0.0;
      (void)y;
    }
    void residual(double, const double* y, const double* yp, double* r) override {
      r[0] = yp[0] - 1.0;
      r[1] = y[1] - y[0];
    }
    void event_roots(double, const double* y, double* g) override { g[0] = y[0] - 1.0; }
    EventAction on_event(double, std::vector<double>&, const std::vector<int>&) override { return EventAction::Stop; }
  } m;
  std::vector<double> y{0.0, 0.0};
  try {
    run_hybrid(m, 0.0, y, ida_options(true), {});
    ADD_FAILURE() << "accepted ida_reduced_state with an algebraic component";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ida_reduced_state needs a system without algebraic"), std::string::npos)
        << e.what();
  }
}

// Absolute tolerances per component: scales of 1 are the scalar tolerance (the same run, on the
// whole and on the live state), a looser one on a component costs fewer steps and stays inside
// it; a list of the wrong length or a scale that is not positive is a named error.
TEST(IdaLiveState, ComponentTolerances) {
  for (bool reduced : {false, true}) {
    std::vector<double> plain{0.0, 0.0, 0.0}, ones = plain;
    TakingTurns a, b;
    b.atol_scale = {1.0, 1.0, 1.0};
    const auto ra = run_hybrid(a, 0.0, plain, ida_options(reduced), {});
    const auto rb = run_hybrid(b, 0.0, ones, ida_options(reduced, true), {});
    EXPECT_EQ(rb.statistics.steps, ra.statistics.steps) << reduced;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(ones[k], plain[k], 1e-12) << k;
  }
  const double ln2 = std::log(2.0);
  std::vector<double> tight{0.0, 0.0, 0.0}, loose = tight;
  TakingTurns a, b;
  b.atol_scale = {1.0, 1.0, 1e4};  // the accumulator y_2 to 1e-8 instead of 1e-12
  const auto ra = run_hybrid(a, 0.0, tight, ida_options(true), {});
  const auto rb = run_hybrid(b, 0.0, loose, ida_options(true, true), {});
  EXPECT_LT(rb.statistics.steps, ra.statistics.steps);
  EXPECT_NEAR(loose[2], 3.0 * (1.0 - ln2), 1e-7);
  EXPECT_NEAR(rb.end_time, 3.0 * ln2, 1e-8);

  TakingTurns short_list;
  short_list.atol_scale = {1.0, 1.0};
  EXPECT_NE(error_of<std::invalid_argument>(short_list, true, true).find("one absolute tolerance per component (2 for 3)"),
            std::string::npos);
  TakingTurns zero;
  zero.atol_scale = {1.0, 0.0, 1.0};
  EXPECT_NE(error_of<std::invalid_argument>(zero, false, true).find("absolute tolerance 0 (need finite, > 0)"),
            std::string::npos);
}
