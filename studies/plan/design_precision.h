#pragma once
// What a chamber profile would teach the fitter: the predicted standard error
// of each coefficient of a model, before the test is run.
//
// 1. The thermal path: the scenario's rig (sim/rig_dynamics.h) integrated
//    under the profile (sim::Simulator::run_thermal), without noise; the
//    sensor readings are the sensor nodes' true temperatures (sim/simulator.h).
// 2. The fitter's own view of that record: the same windows (100 s means),
//    derivatives and regressors (fit/data/prepare.h, fit/model/terms.h), so
//    the design X is the one the fit will see.
// 3. The fitter is least squares on the window means (the intercept
//    profiled), so the coefficients' covariance under the gyro's noise C is
//    the sandwich
//        Cov(b) = (X̃ᵀX̃)⁻¹ X̃ᵀ C X̃ (X̃ᵀX̃)⁻¹,   X̃ the centred design,
//    with C the window means' covariance of every noise component
//    (fit/model/noise_model.h: flicker, Gauss–Markov and random walk in
//    closed form; the white part diagonal, scaled by the simulator's a(T)²
//    at each window's temperature). Not the Fisher information XᵀC⁻¹X: that
//    is the generalised-least-squares estimator's, which our fitter is not;
//    under flicker the two differ, and the sandwich is what a fit achieves.
// 4. A term with a nonlinear parameter (lag's τ, warmup's τ) is fitted by
//    variable projection; as the fitter does for its intervals
//    (fit/pipeline.h), the design is augmented with b_j·∂x_j/∂ln θ_j at the
//    prior b_j, so the coefficient's error includes the parameter's. That
//    linearisation holds only while the parameter is pinned down: where
//    se(ln θ_j) is large the fitted θ wanders over its range and the
//    coefficient with it (on the cycle with lag at 0.002 °/h/°C, a predicted
//    se of 5e-4 became 4.4e-3 over 200 seeds). So se(ln θ_j) is reported,
//    and the search asks it to be at most kLogParameterSe wherever the
//    term's coefficient has a target (studies/plan/search.h).
// 5. A design the fitter would refuse — the scaled correlation matrix's
//    condition number above LinearProblem::kIllConditioned — identifies
//    nothing: every standard error is +∞ and its `refusal` says why.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fit/model/terms.h"
#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"
#include "studies/plan/plan_noise.h"
#include "studies/plan/precision.h"
#include "studies/plan/profiles.h"

namespace gyrotherm::studies::plan {

// The model the test must identify: the terms as fitted, each term's
// nonlinear parameter (NaN without one) and a prior value of each
// coefficient (0 where none is known).
struct PlanModel {
  std::vector<const fit::Term*> terms;
  std::vector<double> parameters;
  std::vector<double> prior;
};

// Where each coefficient's information comes from, for the figure.
struct PrecisionDetail {
  Precision precision;
  std::vector<double> time_s, setpoint_c, chamber_c, sensor_c;  // the thermal trace, every 10 s
  std::vector<double> window_time_s;                           // the fitter's windows
  // Per term, per window: the share of the coefficient's estimate the window
  // carries, w_ji² / Σ_i w_ji² with w_j the row of (X̃ᵀX̃)⁻¹X̃ᵀ (the estimate is
  // Σ_i w_ji y_i); cumulative over time in `cumulative_share`.
  std::vector<std::vector<double>> cumulative_share;
};

class DesignEvaluator {
 public:
  // `base`: the room, start temperature, initial condition, sample rate and
  // chamber of the test (its segments are replaced by each profile).
  DesignEvaluator(sim::Scenario base, sim::RigConfig rig, sim::GyroConfig gyro, PlanNoise noise,
                  PlanModel model);

  // Predicted precision of the profile; thread-safe (each call integrates its own ODE).
  Precision precision(const ChamberProfile& profile) const;
  PrecisionDetail detail(const ChamberProfile& profile) const;

  const PlanModel& model() const { return model_; }
  const PlanNoise& noise() const { return noise_; }
  const sim::Scenario& base() const { return base_; }
  const sim::RigConfig& rig() const { return rig_; }
  const sim::GyroConfig& gyro() const { return gyro_; }
  // The scenario of a profile: `base` with its start and segments.
  sim::Scenario scenario(const ChamberProfile& profile) const;

 private:
  Precision evaluate(const ChamberProfile& profile, PrecisionDetail* detail) const;

  sim::Scenario base_;
  sim::RigConfig rig_;
  sim::GyroConfig gyro_;
  PlanNoise noise_;
  PlanModel model_;
};

}  // namespace gyrotherm::studies::plan
