#include "ida_solver.hpp"

#include "eigen_dense_linear_solver.hpp"
#include "ida_live_roots.hpp"
#include "ida_small_vector_ops.hpp"
#include "small_dense_linear_solver.hpp"

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <cstdlib>
#include <optional>
#include <fmt/format.h>

namespace ringcrush::hinge {

IdaError::IdaError(std::string function, int flag, const std::string& message)
    : std::runtime_error(message), function_(std::move(function)), flag_(flag) {}

namespace {

std::string flag_name(int flag) {
  char* name = IDAGetReturnFlagName(flag);  // allocated by IDA
  std::string result = name ? name : "unknown";
  std::free(name);
  return result;
}

// The one place that turns SUNDIALS return codes into exceptions.
void check_ida(int flag, const char* function, const std::string& last_message = {}) {
  if (flag >= 0) return;
  throw IdaError(function, flag,
                 fmt::format("{} failed with {} ({}){}{}", function, flag_name(flag), flag,
                             last_message.empty() ? "" : ": ", last_message));
}

template <typename T>
T* check_alloc(T* p, const char* function) {
  if (!p) throw IdaError(function, -1, fmt::format("{} returned no object", function));
  return p;
}

class DenseSink final : public JacobianSink {
 public:
  explicit DenseSink(SUNMatrix m) : m_(m) {}
  void set(std::size_t row, std::size_t col, double value) override {
    SM_ELEMENT_D(m_, static_cast<sunindextype>(row), static_cast<sunindextype>(col)) = value;
  }

 private:
  SUNMatrix m_;
};

class BandSink final : public JacobianSink {
 public:
  explicit BandSink(SUNMatrix m) : m_(m) {}
  void set(std::size_t row, std::size_t col, double value) override {
    const auto i = static_cast<sunindextype>(row), j = static_cast<sunindextype>(col);
    if (i - j > SM_LBAND_B(m_) || j - i > SM_UBAND_B(m_))
      throw std::out_of_range(fmt::format("Jacobian entry ({}, {}) outside the band", row, col));
    SM_ELEMENT_B(m_, i, j) = value;
  }

 private:
  SUNMatrix m_;
};

}  // namespace

struct IdaSolver::Impl {
  SUNContext context = nullptr;
  void* ida = nullptr;
  N_Vector y = nullptr, yp = nullptr, id = nullptr, atol = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  IdaOptions options;
  std::string last_message;
  DaeSystem* system = nullptr;
  std::vector<int> masked;  // per root, see IdaSolver::reinit
  // The roots IDA is given (all unless set_live_roots()), in the model's indices; the model's
  // values, of which IDA gets the live ones; a held root's sign change (the model's list).
  IdaLiveRoots live_roots;
  std::optional<std::vector<std::size_t>> pending_live_roots;
  int ida_root_count = 0;
  std::vector<double> model_roots;
  std::string root_failure;

  ~Impl() {
    if (ida) IDAFree(&ida);
    if (linear_solver) SUNLinSolFree(linear_solver);
    if (matrix) SUNMatDestroy(matrix);
    if (atol) N_VDestroy(atol);
    if (id) N_VDestroy(id);
    if (yp) N_VDestroy(yp);
    if (y) N_VDestroy(y);
    if (context) SUNContext_Free(&context);
  }

  void check(int flag, const char* function) {
    check_ida(flag, function, last_message);
    last_message.clear();
  }

  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* user) {
    try {
      static_cast<Impl*>(user)->system->residual(t, N_VGetArrayPointer(y),
                                                 N_VGetArrayPointer(yp), N_VGetArrayPointer(r));
      return 0;
    } catch (...) {
      return -1;  // unrecoverable: IDA stops and reports IDA_RES_FAIL
    }
  }

  static int roots(realtype t, N_Vector y, N_Vector yp, realtype* g, void* user) {
    auto* self = static_cast<Impl*>(user);
    const bool all = self->live_roots.all();
    double* model = all ? g : self->model_roots.data();
    try {
      self->system->roots(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), model);
    } catch (...) {
      return -1;  // IDA_RTFUNC_FAIL
    }
    if (!all) {
      try {
        self->live_roots.check_held(t, model);
      } catch (const std::logic_error& e) {
        self->root_failure = e.what();  // rethrown by run() as it is
        return -1;
      }
    }
    // Masking: a just-fired root reads exactly zero (inactive for IDA) until it has left
    // zero; IDA then re-activates it without reporting a crossing.
    const double tol = self->options.root_mask_tolerance;
    for (std::size_t i = 0; i < self->masked.size(); ++i) {
      const int m = self->masked[i];
      if (m == 0) continue;
      if (std::abs(model[i]) > tol) self->masked[i] = 0;
      else model[i] = (m == 1 || m == -1) ? m * tol : 0.0;
    }
    if (!all) self->live_roots.gather(model, g);
    return 0;
  }

  static int jacobian(realtype t, realtype cj, N_Vector y, N_Vector yp, N_Vector, SUNMatrix J,
                      void* user, N_Vector, N_Vector, N_Vector) {
    SUNMatZero(J);
    auto* system = static_cast<Impl*>(user)->system;
    if (SUNMatGetID(J) == SUNMATRIX_BAND) {
      BandSink sink(J);
      system->jacobian(t, cj, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), sink);
    } else {
      DenseSink sink(J);
      system->jacobian(t, cj, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), sink);
    }
    return 0;
  }

  static void error_handler(int, const char* module, const char* function, char* msg,
                            void* data) {
    static_cast<Impl*>(data)->last_message = fmt::format("{}::{}: {}", module, function, msg);
  }
};

IdaSolver::IdaSolver(DaeSystem& system, double t0, const std::vector<double>& y0,
                     const std::vector<double>& yp0, const IdaOptions& options)
    : impl_(std::make_unique<Impl>()), system_(system), t_(t0), y_(y0), yp_(yp0) {
  const auto n = static_cast<sunindextype>(system.size());
  if (y0.size() != system.size() || yp0.size() != system.size())
    throw std::invalid_argument("IdaSolver: y0 and yp0 must match the system size");
  auto& m = *impl_;
  m.options = options;
  m.system = &system;
  m.check(SUNContext_Create(nullptr, &m.context), "SUNContext_Create");
  m.y = check_alloc(N_VNew_Serial(n, m.context), "N_VNew_Serial");
  m.yp = check_alloc(N_VNew_Serial(n, m.context), "N_VNew_Serial");
  std::copy(y0.begin(), y0.end(), N_VGetArrayPointer(m.y));
  std::copy(yp0.begin(), yp0.end(), N_VGetArrayPointer(m.yp));
  if (options.small_vector_ops) {  // before IDAInit: IDA's own vectors are clones of y
    use_small_vector_ops(m.y);
    use_small_vector_ops(m.yp);
  }

  m.ida = check_alloc(IDACreate(m.context), "IDACreate");
  m.check(IDASetErrHandlerFn(m.ida, &Impl::error_handler, &m), "IDASetErrHandlerFn");
  m.check(IDAInit(m.ida, &Impl::residual, t0, m.y, m.yp), "IDAInit");
  m.check(IDASetUserData(m.ida, &m), "IDASetUserData");
  m.check(IDASStolerances(m.ida, options.relative_tolerance, options.absolute_tolerance),
          "IDASStolerances");
  m.check(IDASetMaxNumSteps(m.ida, options.max_steps), "IDASetMaxNumSteps");
  if (options.max_step > 0.0) m.check(IDASetMaxStep(m.ida, options.max_step), "IDASetMaxStep");
  // Optional inputs survive IDAReInit: set once for every restart.
  if (const auto& g = options.step_growth; g.growth_threshold != 0.0 || g.hold_floor != 0.0 || g.growth_max != 0.0) {
    // IDA's own values for those left at 0 (IDASetEtaFixedStepBounds would take a floor of 0
    // as "never cut", and replace a value out of range by its own without a word).
    const double threshold = g.growth_threshold != 0.0 ? g.growth_threshold : 2.0;
    const double floor = g.hold_floor != 0.0 ? g.hold_floor : 1.0;
    const double most = g.growth_max != 0.0 ? g.growth_max : std::max(2.0, threshold);
    if (!(threshold >= 1.0 && std::isfinite(threshold)) || !(floor > 0.0 && floor <= 1.0) ||
        !(most >= threshold && std::isfinite(most)))
      throw std::invalid_argument(fmt::format(
          "IdaSolver: step growth threshold {}, hold floor {}, growth max {} (need threshold >= 1, 0 < floor <= 1, max >= threshold)",
          threshold, floor, most));
    m.check(IDASetEtaFixedStepBounds(m.ida, floor, threshold), "IDASetEtaFixedStepBounds");
    m.check(IDASetEtaMax(m.ida, most), "IDASetEtaMax");
  }

  if (options.linear_solver == IdaOptions::LinearSolver::Band) {
    m.matrix = check_alloc(
        SUNBandMatrix(n, options.upper_bandwidth, options.lower_bandwidth, m.context),
        "SUNBandMatrix");
    m.linear_solver = check_alloc(SUNLinSol_Band(m.y, m.matrix, m.context), "SUNLinSol_Band");
  } else if (options.linear_solver == IdaOptions::LinearSolver::EigenDense) {
    m.matrix = check_alloc(SUNDenseMatrix(n, n, m.context), "SUNDenseMatrix");
    m.linear_solver = check_alloc(eigen_dense_linear_solver(n, m.context), "eigen_dense_linear_solver");
  } else if (options.linear_solver == IdaOptions::LinearSolver::SmallDense) {
    m.matrix = check_alloc(SUNDenseMatrix(n, n, m.context), "SUNDenseMatrix");
    m.linear_solver = check_alloc(small_dense_linear_solver(n, m.context), "small_dense_linear_solver");
  } else {
    m.matrix = check_alloc(SUNDenseMatrix(n, n, m.context), "SUNDenseMatrix");
    m.linear_solver = check_alloc(SUNLinSol_Dense(m.y, m.matrix, m.context), "SUNLinSol_Dense");
  }
  m.check(IDASetLinearSolver(m.ida, m.linear_solver, m.matrix), "IDASetLinearSolver");
  if (system.has_jacobian()) m.check(IDASetJacFn(m.ida, &Impl::jacobian), "IDASetJacFn");

  const auto mask = system.differential_mask();
  if (!mask.empty()) {
    if (mask.size() != system.size())
      throw std::invalid_argument("IdaSolver: differential mask must match the system size");
    m.id = check_alloc(N_VNew_Serial(n, m.context), "N_VNew_Serial");
    std::copy(mask.begin(), mask.end(), N_VGetArrayPointer(m.id));
    m.check(IDASetId(m.ida, m.id), "IDASetId");
    if (options.suppress_algebraic_error_test)
      m.check(IDASetSuppressAlg(m.ida, SUNTRUE), "IDASetSuppressAlg");
  }

  if (const auto nroots = system.root_count(); nroots > 0) {
    m.check(IDARootInit(m.ida, static_cast<int>(nroots), &Impl::roots), "IDARootInit");
    m.check(IDASetNoInactiveRootWarn(m.ida), "IDASetNoInactiveRootWarn");
    m.ida_root_count = static_cast<int>(nroots);
    m.live_roots = IdaLiveRoots(nroots);
    m.model_roots.assign(nroots, 0.0);
  }
}

IdaSolver::~IdaSolver() = default;

void IdaSolver::pull() {
  const auto n = y_.size();
  std::copy_n(N_VGetArrayPointer(impl_->y), n, y_.begin());
  std::copy_n(N_VGetArrayPointer(impl_->yp), n, yp_.begin());
}

void IdaSolver::calc_initial_conditions(double tout1) {
  auto& m = *impl_;
  if (!m.id) throw std::logic_error("IdaSolver: IDACalcIC needs a differential mask");
  m.check(IDACalcIC(m.ida, IDA_YA_YDP_INIT, tout1), "IDACalcIC");
  m.check(IDAGetConsistentIC(m.ida, m.y, m.yp), "IDAGetConsistentIC");
  pull();
}

void IdaSolver::reinit(double t, const std::vector<double>& y, const std::vector<double>& yp) {
  reinit(t, y, yp, std::vector<int>(system_.root_count(), 0));
}

const std::vector<int>& IdaSolver::root_mask() const { return impl_->masked; }

void IdaSolver::reinit(double t, const std::vector<double>& y, const std::vector<double>& yp,
                       const std::vector<int>& masked) {
  auto& m = *impl_;
  if (y.size() != y_.size() || yp.size() != y_.size())
    throw std::invalid_argument("IdaSolver::reinit: state size does not match the system");
  if (!masked.empty() && masked.size() != system_.root_count())
    throw std::invalid_argument("IdaSolver::reinit: one mask entry per root function");
  // IDAReInit zeroes IDA's counters: keep the totals.
  const IdaStatistics s = statistics();
  before_restarts_ = s;
  ++restarts_;
  m.masked = masked;
  std::copy(y.begin(), y.end(), N_VGetArrayPointer(m.y));
  std::copy(yp.begin(), yp.end(), N_VGetArrayPointer(m.yp));
  m.check(IDAReInit(m.ida, t, m.y, m.yp), "IDAReInit");
  t_ = t;
  y_ = y;
  yp_ = yp;
  m.root_failure.clear();
  if (m.pending_live_roots) {
    // The held roots' signs at the restart, then IDA's root functions resized if needed
    // (IDARootInit reallocates its root arrays only when the number changes).
    std::vector<double> start(system_.root_count(), 0.0);
    if (!m.pending_live_roots->empty())
      system_.roots(t, y_.data(), yp_.data(), start.data());
    m.live_roots.select(*m.pending_live_roots, start);
    m.pending_live_roots.reset();
    if (const auto count = static_cast<int>(m.live_roots.size()); count != m.ida_root_count) {
      m.check(IDARootInit(m.ida, count, &Impl::roots), "IDARootInit");
      m.check(IDASetNoInactiveRootWarn(m.ida), "IDASetNoInactiveRootWarn");
      m.ida_root_count = count;
    }
  }
}

void IdaSolver::set_live_roots(const std::vector<std::size_t>& live) {
  if (system_.root_count() == 0 && !live.empty())
    throw std::invalid_argument("IdaSolver::set_live_roots: the system has no root functions");
  impl_->pending_live_roots = live;
}

void IdaSolver::set_stop_time(double t_stop) {
  impl_->check(IDASetStopTime(impl_->ida, t_stop), "IDASetStopTime");
}

void IdaSolver::set_tolerances(double relative, const std::vector<double>& absolute) {
  auto& m = *impl_;
  if (absolute.size() != y_.size())
    throw std::invalid_argument("IdaSolver::set_tolerances: one absolute tolerance per component");
  if (!m.atol) m.atol = check_alloc(N_VNew_Serial(static_cast<sunindextype>(y_.size()), m.context), "N_VNew_Serial");
  std::copy(absolute.begin(), absolute.end(), N_VGetArrayPointer(m.atol));
  m.check(IDASVtolerances(m.ida, relative, m.atol), "IDASVtolerances");
}

void IdaSolver::set_initial_step(double h) {
  if (!(h >= 0.0) || !std::isfinite(h))
    throw std::invalid_argument(fmt::format("IdaSolver::set_initial_step: h = {} (need finite, >= 0)", h));
  impl_->check(IDASetInitStep(impl_->ida, h), "IDASetInitStep");
}

double IdaSolver::last_step() const {
  realtype h = 0.0;
  impl_->check(IDAGetLastStep(impl_->ida, &h), "IDAGetLastStep");
  return h;
}

void IdaSolver::set_root_direction(const std::vector<int>& direction) {
  if (direction.size() != system_.root_count())
    throw std::invalid_argument("IdaSolver: one direction per root function");
  if (!impl_->live_roots.all())
    throw std::logic_error("IdaSolver::set_root_direction: not with live roots (IDARootInit resets the directions)");
  std::vector<int> copy = direction;
  impl_->check(IDASetRootDirection(impl_->ida, copy.data()), "IDASetRootDirection");
}

IdaSolver::Step IdaSolver::run(double tout, int mode) {
  auto& m = *impl_;
  realtype tret = t_;
  const int flag = IDASolve(m.ida, tout, &tret, m.y, m.yp, mode);
  if (flag == IDA_RTFUNC_FAIL && !m.root_failure.empty()) throw std::logic_error(m.root_failure);
  if (flag < 0) {
    const std::string where = fmt::format("IDASolve at t = {:.9g} s toward {:.9g} s", tret, tout);
    check_ida(flag, where.c_str(), m.last_message);
  }
  t_ = tret;
  pull();
  Step step{t_, flag == IDA_ROOT_RETURN, flag == IDA_TSTOP_RETURN, {}};
  if (step.root_found) {
    step.roots_found.assign(static_cast<std::size_t>(m.ida_root_count), 0);
    m.check(IDAGetRootInfo(m.ida, step.roots_found.data()), "IDAGetRootInfo");
    step.roots_found = m.live_roots.expand(step.roots_found);
  }
  return step;
}

IdaSolver::Step IdaSolver::advance(double tout) { return run(tout, IDA_NORMAL); }
IdaSolver::Step IdaSolver::step(double tout) { return run(tout, IDA_ONE_STEP); }

IdaStatistics IdaSolver::statistics() const {
  auto& m = *impl_;
  IdaStatistics s;
  const IdaStatistics& b = before_restarts_;
  m.check(IDAGetNumSteps(m.ida, &s.steps), "IDAGetNumSteps");
  m.check(IDAGetNumResEvals(m.ida, &s.residual_evaluations), "IDAGetNumResEvals");
  m.check(IDAGetNumJacEvals(m.ida, &s.jacobian_evaluations), "IDAGetNumJacEvals");
  m.check(IDAGetNumNonlinSolvIters(m.ida, &s.nonlinear_iterations), "IDAGetNumNonlinSolvIters");
  m.check(IDAGetNumErrTestFails(m.ida, &s.error_test_failures), "IDAGetNumErrTestFails");
  m.check(IDAGetNumNonlinSolvConvFails(m.ida, &s.nonlinear_convergence_failures),
          "IDAGetNumNonlinSolvConvFails");
  if (system_.root_count() > 0) m.check(IDAGetNumGEvals(m.ida, &s.root_evaluations), "IDAGetNumGEvals");
  s += b;
  return s;
}

}  // namespace ringcrush::hinge
