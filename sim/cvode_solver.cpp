#include "sim/cvode_solver.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cstdlib>
#include <string>

namespace gyrotherm::sim {
namespace {

// Turns a SUNDIALS flag into an exception carrying the function, the flag's
// name and the last message CVODE's error handler captured.
void check(int flag, const char* function, const std::string& last_message) {
  if (flag >= 0) return;
  // CVodeGetReturnFlagName returns a malloc'd string the caller frees.
  char* name = CVodeGetReturnFlagName(flag);
  std::string message = std::string(function) + " failed: " + (name != nullptr ? name : "?");
  std::free(name);
  if (!last_message.empty()) message += " (" + last_message + ")";
  throw SolverError(message);
}

template <class T>
T* check_created(T* ptr, const char* function) {
  if (ptr == nullptr) throw SolverError(std::string(function) + " returned null");
  return ptr;
}

}  // namespace

struct CvodeSolver::Impl {
  OdeSystem& system;
  SUNContext context = nullptr;
  N_Vector y = nullptr;
  N_Vector abs_tol = nullptr;
  N_Vector dense_out = nullptr;  // scratch for dense output, so state_at never allocates
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  void* cvode = nullptr;
  std::string last_message;   // filled by the error handler, never printed
  SolverStatistics before_restart;  // totals from earlier CVODE lifetimes

  explicit Impl(OdeSystem& s) : system(s) {}
  ~Impl() {
    if (cvode != nullptr) CVodeFree(&cvode);
    if (linear_solver != nullptr) SUNLinSolFree(linear_solver);
    if (matrix != nullptr) SUNMatDestroy(matrix);
    if (dense_out != nullptr) N_VDestroy(dense_out);
    if (abs_tol != nullptr) N_VDestroy(abs_tol);
    if (y != nullptr) N_VDestroy(y);
    if (context != nullptr) SUNContext_Free(&context);
  }

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
    auto* self = static_cast<Impl*>(user_data);
    const auto n = static_cast<std::size_t>(N_VGetLength(y));
    return self->system.rhs(t, std::span<const double>(N_VGetArrayPointer(y), n),
                            std::span<double>(N_VGetArrayPointer(ydot), n));
  }

  static void on_error(int, const char*, const char* function, char* msg, void* user_data) {
    auto* self = static_cast<Impl*>(user_data);
    self->last_message = std::string(function) + ": " + msg;
  }

  SolverStatistics current() const {
    SolverStatistics s;
    check(CVodeGetNumSteps(cvode, &s.steps), "CVodeGetNumSteps", last_message);
    long rhs_ls = 0;
    check(CVodeGetNumRhsEvals(cvode, &s.rhs_evaluations), "CVodeGetNumRhsEvals", last_message);
    check(CVodeGetNumLinRhsEvals(cvode, &rhs_ls), "CVodeGetNumLinRhsEvals", last_message);
    s.rhs_evaluations += rhs_ls;
    check(CVodeGetNumJacEvals(cvode, &s.jacobian_evaluations), "CVodeGetNumJacEvals", last_message);
    check(CVodeGetNumLinSolvSetups(cvode, &s.linear_setups), "CVodeGetNumLinSolvSetups",
          last_message);
    check(CVodeGetNumNonlinSolvIters(cvode, &s.nonlinear_iterations), "CVodeGetNumNonlinSolvIters",
          last_message);
    check(CVodeGetNumNonlinSolvConvFails(cvode, &s.nonlinear_failures),
          "CVodeGetNumNonlinSolvConvFails", last_message);
    check(CVodeGetNumErrTestFails(cvode, &s.error_test_failures), "CVodeGetNumErrTestFails",
          last_message);
    return s;
  }
};

namespace {
SolverStatistics operator+(SolverStatistics a, const SolverStatistics& b) {
  a.steps += b.steps;
  a.rhs_evaluations += b.rhs_evaluations;
  a.jacobian_evaluations += b.jacobian_evaluations;
  a.linear_setups += b.linear_setups;
  a.nonlinear_iterations += b.nonlinear_iterations;
  a.nonlinear_failures += b.nonlinear_failures;
  a.error_test_failures += b.error_test_failures;
  a.restarts += b.restarts;
  return a;
}
}  // namespace

CvodeSolver::CvodeSolver(OdeSystem& system, double t0, std::span<const double> y0,
                         const CvodeOptions& options)
    : impl_(std::make_unique<Impl>(system)), t_(t0) {
  Impl& m = *impl_;
  const auto n = static_cast<sunindextype>(system.size());
  if (y0.size() != system.size()) throw SolverError("initial state has the wrong size");
  if (options.absolute_tolerance.size() != 1 && options.absolute_tolerance.size() != system.size())
    throw SolverError("absolute tolerance must have one value or one per component");

  if (SUNContext_Create(nullptr, &m.context) != 0) throw SolverError("SUNContext_Create failed");
  m.y = check_created(N_VNew_Serial(n, m.context), "N_VNew_Serial");
  std::copy(y0.begin(), y0.end(), N_VGetArrayPointer(m.y));
  m.abs_tol = check_created(N_VNew_Serial(n, m.context), "N_VNew_Serial");
  m.dense_out = check_created(N_VNew_Serial(n, m.context), "N_VNew_Serial");
  for (sunindextype i = 0; i < n; ++i) {
    const auto& tol = options.absolute_tolerance;
    N_VGetArrayPointer(m.abs_tol)[i] = tol.size() == 1 ? tol[0] : tol[static_cast<std::size_t>(i)];
  }

  m.cvode = check_created(CVodeCreate(CV_BDF, m.context), "CVodeCreate");
  check(CVodeSetErrHandlerFn(m.cvode, &Impl::on_error, &m), "CVodeSetErrHandlerFn", m.last_message);
  check(CVodeInit(m.cvode, &Impl::rhs, t0, m.y), "CVodeInit", m.last_message);
  check(CVodeSetUserData(m.cvode, &m), "CVodeSetUserData", m.last_message);
  check(CVodeSVtolerances(m.cvode, options.relative_tolerance, m.abs_tol), "CVodeSVtolerances",
        m.last_message);
  m.matrix = check_created(SUNDenseMatrix(n, n, m.context), "SUNDenseMatrix");
  m.linear_solver = check_created(SUNLinSol_Dense(m.y, m.matrix, m.context), "SUNLinSol_Dense");
  check(CVodeSetLinearSolver(m.cvode, m.linear_solver, m.matrix), "CVodeSetLinearSolver",
        m.last_message);
  check(CVodeSetMaxNumSteps(m.cvode, options.max_steps_per_call), "CVodeSetMaxNumSteps",
        m.last_message);
  if (options.max_step_s > 0.0)
    check(CVodeSetMaxStep(m.cvode, options.max_step_s), "CVodeSetMaxStep", m.last_message);
}

CvodeSolver::~CvodeSolver() = default;

double CvodeSolver::step_towards(double t_stop) {
  Impl& m = *impl_;
  check(CVodeSetStopTime(m.cvode, t_stop), "CVodeSetStopTime", m.last_message);
  sunrealtype t_reached = t_;
  const int flag = CVode(m.cvode, t_stop, m.y, &t_reached, CV_ONE_STEP);
  check(flag, "CVode", m.last_message);
  t_ = t_reached;
  return t_;
}

void CvodeSolver::state_at(double t, std::span<double> y) const {
  Impl& m = *impl_;
  check(CVodeGetDky(m.cvode, t, 0, m.dense_out), "CVodeGetDky", m.last_message);
  const double* data = N_VGetArrayPointer(m.dense_out);
  std::copy(data, data + y.size(), y.begin());
}

void CvodeSolver::step_polynomial(StepPolynomial& out) const {
  Impl& m = *impl_;
  const std::size_t n = impl_->system.size();
  out.t_n_ = t_;
  out.size_ = n;
  out.c_.resize(6 * n);  // BDF order q ≤ 5
  out.terms_ = 0;
  double factorial = 1.0;
  for (int k = 0; k <= 5; ++k) {
    // k beyond the current order is CV_BAD_K: that ends the polynomial.
    if (CVodeGetDky(m.cvode, t_, k, m.dense_out) != CV_SUCCESS) break;
    if (k > 1) factorial *= k;
    const double* d = N_VGetArrayPointer(m.dense_out);
    for (std::size_t i = 0; i < n; ++i) out.c_[static_cast<std::size_t>(k) * n + i] = d[i] / factorial;
    out.terms_ = static_cast<std::size_t>(k) + 1;
  }
  if (out.terms_ == 0) throw SolverError("CVodeGetDky failed at the end of a step");
}

void CvodeSolver::StepPolynomial::evaluate(double t, std::span<double> y) const {
  const double dt = t - t_n_;
  const std::size_t count = std::min(size_, y.size());  // the first y.size() components
  // Horner's rule for every component at once (the same operations in the same
  // order per component as one at a time; the inner loop vectorises).
  const double* top = c_.data() + (terms_ - 1) * size_;
  std::copy(top, top + count, y.begin());
  for (std::size_t k = terms_ - 1; k-- > 0;) {
    const double* c = c_.data() + k * size_;
    for (std::size_t i = 0; i < count; ++i) y[i] = y[i] * dt + c[i];
  }
}

void CvodeSolver::restart(double t, std::span<const double> y) {
  Impl& m = *impl_;
  SolverStatistics done = m.current();
  done.restarts = 1;
  m.before_restart = m.before_restart + done;
  std::copy(y.begin(), y.end(), N_VGetArrayPointer(m.y));
  check(CVodeReInit(m.cvode, t, m.y), "CVodeReInit", m.last_message);
  t_ = t;
}

SolverStatistics CvodeSolver::statistics() const {
  return impl_->before_restart + impl_->current();
}

}  // namespace gyrotherm::sim
