#pragma once
// RAII wrapper around SUNDIALS CVODE 6.4 for a small stiff ODE system
//
//     y' = f(t, y),   y(t0) = y0,
//
// integrated with variable-order BDF and Newton iterations on a dense direct
// linear solver (the Jacobian by CVODE's difference quotients). The context,
// vectors, matrix, linear solver and integrator memory are owned here; every
// SUNDIALS return flag is checked and turned into a SolverError that carries
// CVODE's own message. Statistics accumulate across restarts.
//
// Use: step_towards(t_stop) advances one internal step without passing t_stop
// (CVODE's CV_ONE_STEP with a stop time); state_at(t) gives the dense output
// anywhere inside the last step; restart(t, y) re-initialises after a
// discontinuity in f (a profile breakpoint), so the BDF history never spans it.
//
// Reference: Hindmarsh et al., "SUNDIALS: Suite of nonlinear and
// differential/algebraic equation solvers", ACM TOMS 31(3), 2005; the CVODE
// user guide v6.4, "Usage of CVODE" and examples/cvode/CXX_serial.

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyrotherm::sim {

// The ODE a CvodeSolver integrates. rhs must not allocate; it returns 0 on
// success, a positive value for a recoverable failure (CVODE retries with a
// smaller step) and a negative value for an unrecoverable one.
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual std::size_t size() const = 0;
  virtual int rhs(double t, std::span<const double> y, std::span<double> ydot) = 0;
};

struct CvodeOptions {
  double relative_tolerance = 1e-8;    // CVODE reltol
  std::vector<double> absolute_tolerance = {1e-8};  // one value, or one per component
  long max_steps_per_call = 100000;    // CVodeSetMaxNumSteps
  double max_step_s = 0.0;             // 0: no limit
};

struct SolverStatistics {
  long steps = 0;                 // internal BDF steps
  long rhs_evaluations = 0;       // f evaluations by the integrator and the DQ Jacobian
  long jacobian_evaluations = 0;  // dense difference-quotient Jacobians
  long linear_setups = 0;         // Newton matrix factorisations
  long nonlinear_iterations = 0;
  long nonlinear_failures = 0;    // Newton convergence failures
  long error_test_failures = 0;
  long restarts = 0;              // re-initialisations at breakpoints
};

class SolverError : public std::runtime_error {
 public:
  explicit SolverError(const std::string& message) : std::runtime_error(message) {}
};

class CvodeSolver {
 public:
  CvodeSolver(OdeSystem& system, double t0, std::span<const double> y0,
              const CvodeOptions& options = {});
  ~CvodeSolver();
  CvodeSolver(const CvodeSolver&) = delete;
  CvodeSolver& operator=(const CvodeSolver&) = delete;

  // One internal step, never beyond t_stop; returns the time reached.
  double step_towards(double t_stop);
  // Dense output y(t) for t inside the last step (CVodeGetDky, k = 0).
  void state_at(double t, std::span<double> y) const;
  // The interpolating polynomial of the last step, for cheap dense output at
  // many points: y(t) = Σ_k c_k (t − t_n)^k with c_k = y^(k)(t_n)/k!, k ≤ q
  // (CVODE's own Nordsieck polynomial, so identical to state_at up to
  // rounding). Call after each step; valid for t inside that step.
  class StepPolynomial {
   public:
    // The first y.size() components (all of them when y is the state's size).
    void evaluate(double t, std::span<double> y) const;
    double t_n() const { return t_n_; }

   private:
    friend class CvodeSolver;
    double t_n_ = 0.0;
    std::size_t size_ = 0;
    std::size_t terms_ = 0;
    std::vector<double> c_;  // terms_ × size_, c_[k·size + i]
  };
  void step_polynomial(StepPolynomial& out) const;

  // Re-initialise at (t, y) after a discontinuity; counters are kept.
  void restart(double t, std::span<const double> y);

  double time() const { return t_; }
  SolverStatistics statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double t_ = 0.0;
};

}  // namespace gyrotherm::sim
