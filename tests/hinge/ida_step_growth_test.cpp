// IDA's step-size changes after a successful step (IdaOptions::step_growth,
// HybridOptions::ida_step_growth_*; SUNDIALS 6.4 IDASetEtaFixedStepBounds / IDASetEtaMax), on
// x″ = −4x (x = cos 2t): IDA's own values given explicitly change nothing, bit for bit; a
// growth threshold below 2 changes the steps, not the answer (to the tolerance); values IDA
// would quietly replace by its own are named errors, in the solver and in the driver.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hinge/hybrid_system.hpp"
#include "hinge/ida_solver.hpp"

using namespace ringcrush::hinge;

namespace {

class Cosine : public DaeSystem {
 public:
  std::size_t size() const override { return 2; }
  void residual(double, const double* y, const double* yp, double* r) override {
    r[0] = yp[0] - y[1];
    r[1] = yp[1] + 4.0 * y[0];
  }
};

struct Run {
  std::vector<double> y;
  long steps;
};

Run run_to(double t_end, IdaOptions::StepGrowth growth) {
  Cosine c;
  IdaOptions o{.relative_tolerance = 1e-8, .absolute_tolerance = 1e-10};
  o.step_growth = growth;
  IdaSolver ida(c, 0.0, {1.0, 0.0}, {0.0, -4.0}, o);
  ida.set_stop_time(t_end);
  ida.advance(t_end);
  // A restart, as the hybrid driver makes at every event: the options outlive IDAReInit.
  ida.reinit(ida.time(), ida.y(), ida.yp());
  ida.set_stop_time(2.0 * t_end);
  ida.advance(2.0 * t_end);
  return {ida.y(), ida.statistics().steps};
}

}  // namespace

TEST(IdaStepGrowth, IdaOwnValuesGivenExplicitlyAreBitIdentical) {
  const auto own = run_to(5.0, {});
  const auto given = run_to(5.0, {.growth_threshold = 2.0, .hold_floor = 1.0, .growth_max = 2.0});
  EXPECT_EQ(given.y, own.y);
  EXPECT_EQ(given.steps, own.steps);
}

TEST(IdaStepGrowth, LowerThresholdChangesTheStepsNotTheAnswer) {
  const auto own = run_to(5.0, {});
  const auto eager = run_to(5.0, {.growth_threshold = 1.2, .hold_floor = 0.9, .growth_max = 10.0});
  EXPECT_NE(eager.steps, own.steps);
  // x(10) = cos 20; the global error of either run is a few hundred rtol over ~3 periods.
  EXPECT_NEAR(eager.y[0], std::cos(20.0), 1e-5);
  EXPECT_NEAR(own.y[0], std::cos(20.0), 1e-5);
}

TEST(IdaStepGrowth, OutOfRangeIsANamedError) {
  Cosine c;
  for (const IdaOptions::StepGrowth bad : {IdaOptions::StepGrowth{.growth_threshold = 0.5},
                                           IdaOptions::StepGrowth{.hold_floor = 1.5},
                                           IdaOptions::StepGrowth{.growth_threshold = 3.0, .growth_max = 2.5}}) {
    IdaOptions o;
    o.step_growth = bad;
    try {
      IdaSolver ida(c, 0.0, {1.0, 0.0}, {0.0, -4.0}, o);
      ADD_FAILURE() << "accepted threshold " << bad.growth_threshold << ", floor " << bad.hold_floor << ", max "
                    << bad.growth_max;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("step growth threshold"), std::string::npos) << e.what();
    }
  }
}

namespace {

// The smallest hybrid system: x′ = 1, no roots.
class Ramp : public HybridSystem {
 public:
  std::size_t size() const override { return 1; }
  std::size_t root_count() const override { return 0; }
  void event_roots(double, const double*, double*) override {}
  EventAction on_event(double, std::vector<double>&, const std::vector<int>&) override { return EventAction::Continue; }
  void rhs(double, const double*, double* f) override { f[0] = 1.0; }
  void residual(double, const double*, const double* yp, double* r) override { r[0] = yp[0] - 1.0; }
};

}  // namespace

TEST(IdaStepGrowth, DriverNamesTheBadOption) {
  struct Case {
    const char* name;
    void (*set)(HybridOptions&);
  };
  const Case cases[] = {
      {"ida_step_growth_threshold = 0.5", [](HybridOptions& o) { o.ida_step_growth_threshold = 0.5; }},
      {"ida_step_hold_floor = 0", [](HybridOptions& o) { o.ida_step_hold_floor = 0.0; }},
      {"ida_step_hold_floor = 1.5", [](HybridOptions& o) { o.ida_step_hold_floor = 1.5; }},
      {"ida_step_growth_max = 1.5", [](HybridOptions& o) {
         o.ida_step_growth_threshold = 1.7;
         o.ida_step_growth_max = 1.5;
       }},
  };
  for (const auto& c : cases) {
    Ramp ramp;
    HybridOptions o;
    o.end_time = 1.0;
    c.set(o);
    std::vector<double> y{0.0};
    try {
      run_hybrid(ramp, 0.0, y, o, {});
      ADD_FAILURE() << "accepted " << c.name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.name), std::string::npos) << e.what();
    }
  }
}
