// IDA on the live root functions only (hinge/ida_live_roots.hpp, HybridOptions::ida_live_roots):
// on a toy hybrid model whose roots go constant once passed, the live-root run fires the same
// events at the same times as the whole root set, with the model's indices in roots_found while
// IDA's number of root functions shrinks 3 → 2 → 1; a held root that changes sign, and a bad
// list, are named errors.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "hinge/hybrid_system.hpp"

using namespace ringcrush::hinge;

namespace {

// y′ = 1 from 0. Milestones at y = 0.25 and 0.5, each root reading a fixed 1 once its event has
// passed (as Level 3's slots of a mechanism that is no longer available); g_2 always reads 1;
// g_3 = y − 1 stops the run. Live: {0, 1, 3}, then {1, 3}, then {3}.
class Milestones final : public HybridSystem {
 public:
  std::vector<std::size_t> first_live{0, 1, 3};  // what live_roots() reports before the first event
  struct Event {
    double t;
    std::vector<int> fired;
  };
  std::vector<Event> events;
  std::size_t size() const override { return 1; }
  std::size_t root_count() const override { return 4; }
  void rhs(double, const double*, double* f) override { f[0] = 1.0; }
  void residual(double, const double*, const double* yp, double* r) override { r[0] = yp[0] - 1.0; }
  void event_roots(double, const double* y, double* g) override {
    g[0] = passed_ < 1 ? y[0] - 0.25 : 1.0;
    g[1] = passed_ < 2 ? y[0] - 0.5 : 1.0;
    g[2] = 1.0;
    g[3] = y[0] - 1.0;
  }
  EventAction on_event(double t, std::vector<double>&, const std::vector<int>& fired) override {
    events.push_back({t, fired});
    if (fired[3] != 0) return EventAction::Stop;
    ++passed_;
    return EventAction::Continue;
  }
  std::vector<std::size_t> live_roots() const override {
    if (passed_ == 0) return first_live;
    if (passed_ == 1) return {1, 3};
    return {3};
  }

 private:
  int passed_ = 0;
};

HybridOptions ida_options(bool live_roots) {
  HybridOptions o;
  o.integrator = HybridIntegrator::Ida;
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  o.end_time = 10.0;
  o.ida_live_roots = live_roots;
  return o;
}

template <typename Error>
std::string error_of(Milestones& m, bool live_roots = true) {
  std::vector<double> y{0.0};
  try {
    run_hybrid(m, 0.0, y, ida_options(live_roots), {});
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

// Events at t = 0.25, 0.5, 1 (closed form to 1e-9 s), the same on both root sets to 1e-12 s,
// each reported at the model's index (the last one is IDA's only root, the model's g_3).
TEST(IdaLiveRoots, SameEventsAsTheWholeRootSet) {
  Milestones whole, live;
  std::vector<double> yw{0.0}, yl{0.0};
  const auto rw = run_hybrid(whole, 0.0, yw, ida_options(false), {});
  const auto rl = run_hybrid(live, 0.0, yl, ida_options(true), {});
  ASSERT_EQ(live.events.size(), 3u);
  ASSERT_EQ(whole.events.size(), 3u);
  const double at[] = {0.25, 0.5, 1.0};
  const std::size_t index[] = {0, 1, 3};
  for (std::size_t e = 0; e < 3; ++e) {
    EXPECT_NEAR(live.events[e].t, at[e], 1e-9) << e;
    EXPECT_NEAR(live.events[e].t, whole.events[e].t, 1e-12) << e;
    std::vector<int> expected(4, 0);
    expected[index[e]] = 1;
    EXPECT_EQ(live.events[e].fired, expected) << e;
    EXPECT_EQ(live.events[e].fired, whole.events[e].fired) << e;
  }
  EXPECT_TRUE(rl.stopped_by_model);
  EXPECT_EQ(rl.statistics.events, rw.statistics.events);
  EXPECT_NEAR(yl[0], 1.0, 1e-9);
}

// g_0 declared held before the first event though it crosses at t = 0.25: the check on every
// root evaluation IDA asks for names it, instead of the event being missed.
TEST(IdaLiveRoots, HeldRootThatChangesSignIsANamedError) {
  Milestones wrong;
  wrong.first_live = {1, 3};
  const std::string e = error_of<std::logic_error>(wrong);
  EXPECT_NE(e.find("live_roots: root 0 is held but changed sign"), std::string::npos) << e;
  EXPECT_TRUE(wrong.events.empty());
  // The whole root set does not read the list: the same model runs to its end.
  Milestones ignored;
  ignored.first_live = {1, 3};
  EXPECT_EQ(error_of<std::exception>(ignored, false), "no error");
  EXPECT_EQ(ignored.events.size(), 3u);
}

TEST(IdaLiveRoots, BadListsAreNamedErrors) {
  Milestones unsorted;
  unsorted.first_live = {3, 0, 1};
  EXPECT_NE(error_of<std::invalid_argument>(unsorted).find("live_roots: must be ascending and distinct"),
            std::string::npos);
  Milestones outside;
  outside.first_live = {0, 1, 4};
  EXPECT_NE(error_of<std::invalid_argument>(outside).find("live_roots: root 4 outside the 4 root functions"),
            std::string::npos);
}
