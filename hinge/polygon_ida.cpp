#include "polygon_ida.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"  // inside Eigen's SparseLU
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#pragma GCC diagnostic pop
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <stdexcept>

namespace ringcrush::hinge {

namespace {

std::string flag_name(int flag) {
  char* name = IDAGetReturnFlagName(flag);
  std::string result = name ? name : "unknown";
  std::free(name);
  return result;
}

// Every SUNDIALS return code of this file passes here (STYLE practice 9).
void check(int flag, const char* function, const std::string& message = {}) {
  if (flag >= 0) return;
  throw IdaError(function, flag,
                 fmt::format("{} failed with {} ({}){}{}", function, flag_name(flag), flag,
                             message.empty() ? "" : ": ", message));
}

}  // namespace

struct PolygonIdaSolver::Impl {
  PolygonChain* system = nullptr;
  PolygonJacobian jacobian_kind = PolygonJacobian::Analytic;
  SUNContext context = nullptr;
  void* ida = nullptr;
  N_Vector y = nullptr, yp = nullptr, atol = nullptr;
  SUNLinearSolver ls = nullptr;
  SUNMatrix jacobian = nullptr;  // direct solver: CSC iteration matrix
  std::vector<sunindextype> last_pointers, last_indices;  // its pattern at the last setup
  std::vector<sunindextype> csc_pointers, csc_indices;    // pattern of the cached slot map
  std::vector<std::int64_t> keys;                         // (row, col) of each triplet
  std::vector<std::size_t> slot;                          // triplet → CSC position
  std::vector<std::size_t> diagonal_slot;                 // (i, i) → CSC position
  std::vector<double> stiffness;  // −∂φ/∂y on the cached pattern, from the last formation
  int reuse_steps = 0;            // PolygonIdaOptions::jacobian_reuse_steps
  long formations = 0, formed_at_step = 0;
  long rebuilds = 0, remaps = 0;  // new patterns; sequence changes kept on the old pattern
  double pattern_slack = 0.0;     // PolygonIdaOptions::pattern_slack
  bool keep_old_entries = false;  // map_onto_pattern → build_pattern
  std::vector<char> used;
  std::vector<std::size_t> new_slot;
  // build_pattern scratch
  std::vector<int> entry_row, entry_col, row_mark;
  std::vector<std::size_t> column_start, column_entries, fill_at, row_slot;
  std::vector<sunindextype> column_rows;
  std::array<long, 2> formed_failures{0, 0};  // IDA's convergence / error-test failures then
  long symbolic = 0;
  std::vector<PolygonChain::Triplet> triplets;
  std::vector<Eigen::Triplet<double>> eigen_triplets;
  Eigen::SparseMatrix<double> matrix;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::VectorXd rhs, sol;
  long setups = 0;
  std::string last_message;
  std::vector<PolygonIdaStep>* step_log = nullptr;
  N_Vector error_estimate = nullptr, error_weights = nullptr;  // step log only

  ~Impl() {
    if (ida) IDAFree(&ida);
    if (ls) SUNLinSolFree(ls);
    if (jacobian) SUNMatDestroy(jacobian);
    if (atol) N_VDestroy(atol);
    if (error_estimate) N_VDestroy(error_estimate);
    if (error_weights) N_VDestroy(error_weights);
    if (yp) N_VDestroy(yp);
    if (y) N_VDestroy(y);
    if (context) SUNContext_Free(&context);
  }

  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* user) {
    try {
      static_cast<Impl*>(user)->system->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp),
                                                 N_VGetArrayPointer(r));
      return 0;
    } catch (...) {
      return -1;
    }
  }

  // ∂F/∂y + cj ∂F/∂y′ into `matrix`, compressed columns, duplicate entries summed.
  void assemble(realtype t, N_Vector state, N_Vector state_rate, N_Vector r, realtype cj) {
    triplets_at(t, state, state_rate, r, cj);
    eigen_triplets.clear();
    eigen_triplets.reserve(triplets.size());
    for (const auto& e : triplets) eigen_triplets.emplace_back(e.row, e.col, e.value);
    const auto n = static_cast<Eigen::Index>(system->size());
    matrix.resize(n, n);
    matrix.setFromTriplets(eigen_triplets.begin(), eigen_triplets.end());
    matrix.makeCompressed();
  }

  // Direct solver: the same matrix copied into IDA's CSC SUNMatrix. KLU reuses its symbolic
  // analysis (ordering, pattern) between setups, so a changed contact pattern must reset it.
  // The triplets (analytic or differences) of the current state.
  void triplets_at(realtype t, N_Vector state, N_Vector state_rate, N_Vector r, realtype cj) {
    if (jacobian_kind == PolygonJacobian::Analytic)
      system->analytic_jacobian(t, cj, N_VGetArrayPointer(state), triplets);
    else
      system->sparse_jacobian(t, cj, N_VGetArrayPointer(state), N_VGetArrayPointer(state_rate),
                              N_VGetArrayPointer(r), triplets);
  }

  // Direct solver: the matrix into IDA's CSC SUNMatrix. F = μ y′ − φ(t, y), so the iteration
  // matrix is −∂φ/∂y + cj diag μ: `stiffness` keeps −∂φ/∂y on the cached pattern and each
  // setup adds cj μ on the diagonal slots (a copy and n additions). −∂φ/∂y is formed anew
  // (a "formation") unless options.jacobian_reuse_steps allows the last one to serve: IDA
  // calls a setup whenever cj has moved by more than cj_setup_ratio, although the state has
  // hardly moved. The analytic entries come in the same sequence while the contact pattern
  // stays the same, so they are added straight into their slots
  // (PolygonChain::analytic_jacobian_scatter); a changed sequence falls back to triplets and
  // a new pattern. KLU reuses its symbolic analysis (ordering, pattern) between setups, so a
  // changed pattern resets it.
  static int jacobian_fn(realtype t, realtype cj, N_Vector y, N_Vector yp, N_Vector r, SUNMatrix J,
                         void* user, N_Vector, N_Vector, N_Vector) {
    auto& m = *static_cast<Impl*>(user);
    try {
      if (!m.reuse_allowed()) m.form_stiffness(t, y, yp, r);
      const std::size_t n = m.system->size(), nnz = m.csc_indices.size();
      if (static_cast<std::size_t>(SUNSparseMatrix_NNZ(J)) != nnz &&
          SUNSparseMatrix_Reallocate(J, static_cast<sunindextype>(nnz)) != 0)
        return -1;
      sunindextype* pointers = SUNSparseMatrix_IndexPointers(J);
      sunindextype* indices = SUNSparseMatrix_IndexValues(J);
      double* data = SUNSparseMatrix_Data(J);
      std::copy(m.csc_pointers.begin(), m.csc_pointers.end(), pointers);
      std::copy(m.csc_indices.begin(), m.csc_indices.end(), indices);
      std::copy(m.stiffness.begin(), m.stiffness.end(), data);
      const auto& mu = m.system->rate_coefficients();
      for (std::size_t i = 0; i < n; ++i) data[m.diagonal_slot[i]] += cj * mu[i];
      const bool same = m.last_pointers.size() == n + 1 && m.last_indices.size() == nnz &&
                        std::equal(pointers, pointers + n + 1, m.last_pointers.begin()) &&
                        std::equal(indices, indices + nnz, m.last_indices.begin());
      if (!same) {
        m.last_pointers.assign(pointers, pointers + n + 1);
        m.last_indices.assign(indices, indices + nnz);
        if (SUNLinSol_KLUReInit(m.ls, J, static_cast<sunindextype>(nnz), SUNKLU_REINIT_PARTIAL) != 0)
          return -1;
        ++m.symbolic;
      }
      ++m.setups;
      return 0;
    } catch (...) {
      return -1;
    }
  }

  // May this setup keep the last −∂φ/∂y? Only within jacobian_reuse_steps accepted steps of
  // its formation and while no Newton iteration has failed to converge or step failed its
  // error test since (IDA's own counters): a failure may come from a stale matrix (a hinge
  // that started to yield, a contact that closed), and IDA does not retry with a fresh one
  // after a setup, so the retry must bring it.
  bool reuse_allowed() {
    if (reuse_steps <= 0) return false;
    long steps = 0, convergence_failures = 0, error_failures = 0;
    check(IDAGetNumSteps(ida, &steps), "IDAGetNumSteps");
    check(IDAGetNumNonlinSolvConvFails(ida, &convergence_failures), "IDAGetNumNonlinSolvConvFails");
    check(IDAGetNumErrTestFails(ida, &error_failures), "IDAGetNumErrTestFails");
    const bool reuse = !stiffness.empty() && steps - formed_at_step < reuse_steps &&
                       convergence_failures == formed_failures[0] && error_failures == formed_failures[1];
    if (!reuse) {
      formed_at_step = steps;
      formed_failures = {convergence_failures, error_failures};
    }
    return reuse;
  }

  // −∂φ/∂y at (t, y) into `stiffness` (cj = 0: the diagonal slots get μ's share at setup).
  void form_stiffness(realtype t, N_Vector state, N_Vector state_rate, N_Vector r) {
    ++formations;
    if (jacobian_kind == PolygonJacobian::Analytic && !keys.empty()) {
      stiffness.assign(csc_indices.size(), 0.0);
      PolygonChain::JacobianScatter into;
      into.keys = keys.data();
      into.slots = slot.data();
      into.count = keys.size();
      into.data = stiffness.data();
      if (system->analytic_jacobian_scatter(t, 0.0, N_VGetArrayPointer(state), into)) return;
    }
    triplets_at(t, state, state_rate, r, 0.0);
    bool cached = slot.size() == triplets.size();
    for (std::size_t k = 0; cached && k < triplets.size(); ++k) cached = keys[k] == key(triplets[k]);
    if (!cached && !map_onto_pattern()) build_pattern();
    stiffness.assign(csc_indices.size(), 0.0);
    for (std::size_t k = 0; k < triplets.size(); ++k) stiffness[slot[k]] += triplets[k].value;
  }

  static std::int64_t key(const PolygonChain::Triplet& e) {
    return PolygonChain::jacobian_key(static_cast<std::size_t>(e.row), static_cast<std::size_t>(e.col));
  }

  // A new entry sequence (a contact pair came or went) whose entries all lie in the current
  // pattern keeps it: only the slots are looked up, and KLU keeps its symbolic analysis
  // (the absent entries are explicit zeros). Contacts flicker in and out of the "near"
  // band, so many sequence changes are such returns. Fails when an entry is new (then
  // build_pattern keeps the old entries too if they stay within the slack) or when unused
  // entries would make up more than pattern_slack of the pattern.
  bool map_onto_pattern() {
    keep_old_entries = false;
    if (pattern_slack <= 0.0 || csc_indices.empty()) return false;
    const std::size_t nnz = csc_indices.size();
    used.assign(nnz, 0);
    std::size_t distinct = 0, missing = 0;
    new_slot.resize(triplets.size());
    for (std::size_t k = 0; k < triplets.size(); ++k) {
      const auto& e = triplets[k];
      const auto first = csc_indices.begin() + csc_pointers[static_cast<std::size_t>(e.col)];
      const auto last = csc_indices.begin() + csc_pointers[static_cast<std::size_t>(e.col) + 1];
      const auto at = std::lower_bound(first, last, static_cast<sunindextype>(e.row));
      if (at == last || *at != e.row) {
        ++missing;
        continue;
      }
      new_slot[k] = static_cast<std::size_t>(at - csc_indices.begin());
      if (!used[new_slot[k]]) {
        used[new_slot[k]] = 1;
        ++distinct;
      }
    }
    const auto unused = static_cast<double>(nnz - distinct);
    if (missing > 0) {
      keep_old_entries = unused <= pattern_slack * static_cast<double>(nnz + missing);
      return false;
    }
    if (unused > pattern_slack * static_cast<double>(nnz)) return false;
    slot.swap(new_slot);
    keys.resize(triplets.size());
    for (std::size_t k = 0; k < triplets.size(); ++k) keys[k] = key(triplets[k]);
    ++remaps;
    return true;
  }

  // The CSC pattern of the current triplets, each triplet's slot in it and the diagonal's
  // slots (every diagonal entry is emitted); with keep_old_entries the previous pattern's
  // entries stay in it as zeros. Built by bucketing the entries per column, then per
  // column marking each row once, sorting the column's distinct rows (~20) and reading
  // each entry's slot from a row → slot scratch: no global sort, no search per entry (this
  // ran at every changed entry sequence, ~1 ms each with Eigen's setFromTriplets).
  void build_pattern() {
    ++rebuilds;
    const std::size_t n = system->size();
    const std::size_t old_entries = keep_old_entries ? csc_indices.size() : 0;
    const std::size_t total = triplets.size() + old_entries;
    // Entry e < triplets.size() is triplet e, the others the old pattern's entries.
    entry_row.resize(total);
    entry_col.resize(total);
    for (std::size_t k = 0; k < triplets.size(); ++k) {
      entry_row[k] = triplets[k].row;
      entry_col[k] = triplets[k].col;
    }
    for (std::size_t c = 0, e = triplets.size(); old_entries > 0 && c < n; ++c)
      for (auto i = csc_pointers[c]; i < csc_pointers[c + 1]; ++i, ++e) {
        entry_row[e] = static_cast<int>(csc_indices[static_cast<std::size_t>(i)]);
        entry_col[e] = static_cast<int>(c);
      }
    column_start.assign(n + 1, 0);
    for (std::size_t e = 0; e < total; ++e) ++column_start[static_cast<std::size_t>(entry_col[e]) + 1];
    for (std::size_t c = 0; c < n; ++c) column_start[c + 1] += column_start[c];
    column_entries.resize(total);
    fill_at.assign(column_start.begin(), column_start.end() - 1);
    for (std::size_t e = 0; e < total; ++e) column_entries[fill_at[static_cast<std::size_t>(entry_col[e])]++] = e;
    row_mark.assign(n, 0);
    row_slot.resize(n);
    csc_pointers.assign(n + 1, 0);
    csc_indices.clear();
    slot.resize(triplets.size());
    diagonal_slot.assign(n, 0);
    std::vector<sunindextype>& rows = column_rows;
    for (std::size_t c = 0; c < n; ++c) {
      rows.clear();
      const auto mark = static_cast<int>(c) + 1;
      for (std::size_t i = column_start[c]; i < column_start[c + 1]; ++i) {
        const auto r = static_cast<std::size_t>(entry_row[column_entries[i]]);
        if (row_mark[r] != mark) {
          row_mark[r] = mark;
          rows.push_back(static_cast<sunindextype>(r));
        }
      }
      std::sort(rows.begin(), rows.end());
      for (const auto r : rows) {
        row_slot[static_cast<std::size_t>(r)] = csc_indices.size();
        csc_indices.push_back(r);
      }
      csc_pointers[c + 1] = static_cast<sunindextype>(csc_indices.size());
      for (std::size_t i = column_start[c]; i < column_start[c + 1]; ++i)
        if (column_entries[i] < triplets.size())
          slot[column_entries[i]] = row_slot[static_cast<std::size_t>(entry_row[column_entries[i]])];
      if (row_mark[c] != mark) throw std::logic_error("PolygonIdaSolver: a diagonal entry is missing");
      diagonal_slot[c] = row_slot[c];
    }
    keys.resize(triplets.size());
    for (std::size_t k = 0; k < triplets.size(); ++k) keys[k] = key(triplets[k]);
  }

  // Krylov solver's preconditioner setup: sparse LU of the same matrix.
  static int setup(realtype t, N_Vector y, N_Vector yp, N_Vector r, realtype cj, void* user) {
    auto& m = *static_cast<Impl*>(user);
    try {
      m.assemble(t, y, yp, r, cj);
      m.lu.analyzePattern(m.matrix);
      m.lu.factorize(m.matrix);
      ++m.setups;
      return m.lu.info() == Eigen::Success ? 0 : 1;  // 1: recoverable, IDA retries
    } catch (...) {
      return -1;
    }
  }

  static int solve(realtype, N_Vector, N_Vector, N_Vector, N_Vector rvec, N_Vector zvec, realtype,
                   realtype, void* user) {
    auto& m = *static_cast<Impl*>(user);
    const auto n = static_cast<Eigen::Index>(m.system->size());
    m.rhs = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(rvec), n);
    m.sol = m.lu.solve(m.rhs);
    if (m.lu.info() != Eigen::Success) return 1;
    std::copy_n(m.sol.data(), n, N_VGetArrayPointer(zvec));
    return 0;
  }

  static void error_handler(int, const char* module, const char* function, char* msg, void* data) {
    static_cast<Impl*>(data)->last_message = fmt::format("{}::{}: {}", module, function, msg);
  }
};

PolygonIdaSolver::PolygonIdaSolver(PolygonChain& system, double t0, const std::vector<double>& y0,
                                   const PolygonIdaOptions& options)
    : impl_(std::make_unique<Impl>()), t_(t0), y_(y0) {
  auto& m = *impl_;
  m.system = &system;
  m.jacobian_kind = options.jacobian;
  if (options.jacobian_reuse_steps < 0)
    throw std::invalid_argument(fmt::format("PolygonIdaSolver: jacobian_reuse_steps {} must be ≥ 0",
                                            options.jacobian_reuse_steps));
  m.reuse_steps = options.jacobian_reuse_steps;
  if (!(options.pattern_slack >= 0.0 && options.pattern_slack < 1.0))
    throw std::invalid_argument(fmt::format("PolygonIdaSolver: pattern_slack {} must be in [0, 1)", options.pattern_slack));
  m.pattern_slack = options.pattern_slack;
  if (options.klu_ordering < 0 || options.klu_ordering > 2)
    throw std::invalid_argument(
        fmt::format("PolygonIdaSolver: klu_ordering {} must be 0 (AMD), 1 (COLAMD) or 2 (natural)", options.klu_ordering));
  const auto n = static_cast<sunindextype>(system.size());
  if (y0.size() != system.size()) throw std::invalid_argument("PolygonIdaSolver: state size");
  if (!(options.velocity_tolerance_factor > 0) || !(options.plastic_tolerance_factor > 0))
    throw std::invalid_argument(fmt::format(
        "PolygonIdaSolver: velocity_tolerance_factor {} and plastic_tolerance_factor {} must be positive",
        options.velocity_tolerance_factor, options.plastic_tolerance_factor));
  check(SUNContext_Create(nullptr, &m.context), "SUNContext_Create");
  m.y = N_VNew_Serial(n, m.context);
  m.yp = N_VNew_Serial(n, m.context);
  m.atol = N_VNew_Serial(n, m.context);
  if (!m.y || !m.yp || !m.atol) throw IdaError("N_VNew_Serial", -1, "N_VNew_Serial returned no vector");
  std::copy(y0.begin(), y0.end(), N_VGetArrayPointer(m.y));
  system.rhs(t0, y0.data(), N_VGetArrayPointer(m.yp));  // consistent y′0 (μ is diagonal)
  const auto scales = system.component_scales();
  for (std::size_t i = 0; i < scales.size(); ++i)
    N_VGetArrayPointer(m.atol)[i] = options.absolute_scale * scales[i];
  const auto kinds = system.component_kinds();
  for (std::size_t i = 0; i < kinds.size(); ++i)
    if (kinds[i] == PolygonChain::Component::Velocity)
      N_VGetArrayPointer(m.atol)[i] *= options.velocity_tolerance_factor;
    else if (kinds[i] == PolygonChain::Component::Plastic)
      N_VGetArrayPointer(m.atol)[i] *= options.plastic_tolerance_factor;

  m.ida = IDACreate(m.context);
  if (!m.ida) throw IdaError("IDACreate", -1, "IDACreate returned no memory");
  check(IDASetErrHandlerFn(m.ida, &Impl::error_handler, &m), "IDASetErrHandlerFn");
  check(IDAInit(m.ida, &Impl::residual, t0, m.y, m.yp), "IDAInit");
  check(IDASetUserData(m.ida, &m), "IDASetUserData");
  check(IDASVtolerances(m.ida, options.relative_tolerance, m.atol), "IDASVtolerances");
  check(IDASetMaxNumSteps(m.ida, options.max_steps), "IDASetMaxNumSteps");
  if (options.max_step > 0) check(IDASetMaxStep(m.ida, options.max_step), "IDASetMaxStep");
  if (options.initial_step > 0) check(IDASetInitStep(m.ida, options.initial_step), "IDASetInitStep");
  check(IDASetMaxOrd(m.ida, options.max_order), "IDASetMaxOrd");
  check(IDASetDeltaCjLSetup(m.ida, options.cj_setup_ratio), "IDASetDeltaCjLSetup");
  check(IDASetNonlinConvCoef(m.ida, options.nonlinear_convergence_coefficient), "IDASetNonlinConvCoef");
  if (options.step_log) {
    m.step_log = options.step_log;
    m.error_estimate = N_VNew_Serial(n, m.context);
    m.error_weights = N_VNew_Serial(n, m.context);
    if (!m.error_estimate || !m.error_weights)
      throw IdaError("N_VNew_Serial", -1, "N_VNew_Serial returned no vector");
  }
  if (options.linear_solver == PolygonLinearSolver::Direct) {
    // jacobian_fn sizes it to the pattern (IDA zeroes all of its room at every setup).
    m.jacobian = SUNSparseMatrix(n, n, 20 * n, CSC_MAT, m.context);
    if (!m.jacobian) throw IdaError("SUNSparseMatrix", -1, "SUNSparseMatrix returned no matrix");
    m.ls = SUNLinSol_KLU(m.y, m.jacobian, m.context);
    if (!m.ls) throw IdaError("SUNLinSol_KLU", -1, "SUNLinSol_KLU returned no solver");
    check(SUNLinSol_KLUSetOrdering(m.ls, options.klu_ordering), "SUNLinSol_KLUSetOrdering");
    check(IDASetLinearSolver(m.ida, m.ls, m.jacobian), "IDASetLinearSolver");
    check(IDASetJacFn(m.ida, &Impl::jacobian_fn), "IDASetJacFn");
  } else {
    m.ls = SUNLinSol_SPGMR(m.y, SUN_PREC_LEFT, 10, m.context);
    if (!m.ls) throw IdaError("SUNLinSol_SPGMR", -1, "SUNLinSol_SPGMR returned no solver");
    check(IDASetLinearSolver(m.ida, m.ls, nullptr), "IDASetLinearSolver");
    check(IDASetPreconditioner(m.ida, &Impl::setup, &Impl::solve), "IDASetPreconditioner");
  }
}

PolygonIdaSolver::~PolygonIdaSolver() = default;

void PolygonIdaSolver::log_step(Impl& m, double t) {
  PolygonIdaStep step;
  step.t = t;
  check(IDAGetLastStep(m.ida, &step.h), "IDAGetLastStep");
  check(IDAGetLastOrder(m.ida, &step.order), "IDAGetLastOrder");
  check(IDAGetEstLocalErrors(m.ida, m.error_estimate), "IDAGetEstLocalErrors");
  check(IDAGetErrWeights(m.ida, m.error_weights), "IDAGetErrWeights");
  const double* e = N_VGetArrayPointer(m.error_estimate);
  const double* w = N_VGetArrayPointer(m.error_weights);
  const auto n = static_cast<long>(N_VGetLength(m.error_estimate));
  for (long i = 0; i < n; ++i) {
    const double v = std::abs(e[i] * w[i]);
    if (v > step.worst_weighted_error) {
      step.worst_weighted_error = v;
      step.worst_component = i;
    }
  }
  m.step_log->push_back(step);
}

double PolygonIdaSolver::advance(double tout) {
  auto& m = *impl_;
  realtype tret = t_;
  int flag = 0;
  if (!m.step_log) {
    flag = IDASolve(m.ida, tout, &tret, m.y, m.yp, IDA_NORMAL);
  } else {
    // One step at a time up to tout, then the same interpolation IDA_NORMAL does.
    realtype treached = t_;
    check(IDAGetCurrentTime(m.ida, &treached), "IDAGetCurrentTime");
    while (treached < tout && flag >= 0) {
      flag = IDASolve(m.ida, tout, &treached, m.y, m.yp, IDA_ONE_STEP);
      if (flag < 0) break;
      log_step(m, treached);
    }
    tret = treached;
    if (flag >= 0 && treached >= tout) {
      check(IDAGetDky(m.ida, tout, 0, m.y), "IDAGetDky");
      tret = tout;
    }
  }
  if (flag < 0) {
    const std::string where = fmt::format("IDASolve at t = {:.9g} s toward {:.9g} s", tret, tout);
    check(flag, where.c_str(), m.last_message);
  }
  t_ = tret;
  std::copy_n(N_VGetArrayPointer(m.y), y_.size(), y_.begin());
  return t_;
}

PolygonIdaStatistics PolygonIdaSolver::statistics() const {
  auto& m = *impl_;
  PolygonIdaStatistics s;
  check(IDAGetNumSteps(m.ida, &s.steps), "IDAGetNumSteps");
  check(IDAGetNumResEvals(m.ida, &s.residual_evaluations), "IDAGetNumResEvals");
  check(IDAGetNumNonlinSolvIters(m.ida, &s.nonlinear_iterations), "IDAGetNumNonlinSolvIters");
  check(IDAGetNumErrTestFails(m.ida, &s.error_test_failures), "IDAGetNumErrTestFails");
  check(IDAGetNumNonlinSolvConvFails(m.ida, &s.nonlinear_convergence_failures),
        "IDAGetNumNonlinSolvConvFails");
  check(IDAGetNumLinIters(m.ida, &s.linear_iterations), "IDAGetNumLinIters");
  s.preconditioner_setups = m.setups;
  s.symbolic_factorisations = m.symbolic;
  s.jacobian_formations = m.formations;
  s.pattern_rebuilds = m.rebuilds;
  s.pattern_remaps = m.remaps;
  return s;
}

}  // namespace ringcrush::hinge
