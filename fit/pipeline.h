#pragma once
// The fitting pipeline (docs/architecture.md, "The paths of data"):
//
//   1–3. read, clean and average the record (fit/data/prepare.h);
//   4. build the model's regressors from the averaged series (fit/model/terms.h);
//   5. fit with the chosen engine (fit/engines/); b0 is the mean residual;
//   6. report the instability (std of the window averages) before and after.
//
// Nonlinear term parameters (warmup's τ, hyst's dead band) are found by
// variable projection: for a candidate parameter the linear coefficients are
// the exact least-squares ones, so the parameter is chosen to minimise the
// least-squares σ by a bounded 1-D search (a log-spaced grid, then Brent's
// method (Boost.Math) around the best grid point; one parameter at a time,
// repeated);
// the chosen engine then fits the linear coefficients at that parameter.
//
// Their 95 % intervals (with ols, whose intervals are autocorrelation-robust)
// come from the linearised model: near the optimum,
//     B(θ) ≈ B(θ̂) + b_j·∂x_j/∂(ln θ_j)·δ_j,
// so ols on the design augmented with the columns b_j·∂x_j/∂(ln θ_j)
// (central differences, step 1e-4 in ln θ) gives δ_j's interval [lo, hi]
// with the same robust covariance as the coefficients', and θ_j's interval is
// θ̂_j·[e^lo, e^hi]. The coefficients' intervals are taken from the same
// augmented fit, so that they carry the parameters' uncertainty too (a
// coefficient whose regressor moves with θ is far less certain than it looks
// at θ̂ held fixed). A parameter whose regressor is not smooth in it (hyst's
// dead band), whose column vanishes, or that sits on its search bound gets
// none.
//
// Reference: Golub & Pereyra, "Separable nonlinear least squares: the
// variable projection method and its applications", Inverse Problems 19 (2003).

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fit/engines/engine.h"
#include "fit/data/prepare.h"
#include "fit/model/noise_model.h"
#include "fit/model/terms.h"
#include "fit/record_support.h"

namespace gyrotherm::fit {

// `options` reading every log column the terms name (fit/model/terms.h).
PipelineOptions reading_columns_of(PipelineOptions options, const std::vector<const Term*>& terms);

// Throws InputError if a term needs a column the data lacks (e.g. grad without temp2_c).
void check_columns(const std::vector<const Term*>& terms, const PreparedData& data,
                   const ColumnMap& columns);

// A temperature sensor that lags the gyro's temperature by τ reads T − τ·dT/dt
// (first order): a rate term's coefficient then takes up part of the
// temperature terms' (dT/dt read late looks like a rate effect), and a
// gradient's its share. The record alone cannot tell a lag from a rate
// effect, so for each rate and gradient term the fit says which lag would
// move its coefficient by its own 95 % half-width: the model refitted with
// the temperatures de-lagged by 10 s more than given (--sensor-tau), the
// coefficient's change scaled.
struct LagSensitivity {
  std::size_t term = 0;       // index into ModelFit::terms
  double lag_s = 0;           // the lag that moves it by its half-width (∞: none does)
};
// Below this a lag is common in practice (a sensor mounted on the case, tens
// of seconds behind the gyro block): the report cautions.
inline constexpr double kPlausibleSensorLagS = 60.0;

struct ModelFit {
  std::vector<const Term*> terms;
  std::vector<double> parameters;  // per term, NaN where the term has none
  // 95 % interval of each parameter (ols only; absent where the term has
  // none or it cannot be had, see above).
  std::vector<std::optional<Interval>> parameter_intervals;
  Coefficients coefficients;       // physical units
  FitResult engine;
  double instability_before_dph = 0.0;
  double instability_after_dph = 0.0;  // two-pass σ of the residual
  double optimum_dph = 0.0;            // the exact least-squares σ for the same terms and parameters
  std::size_t points = 0;
  // Per window: the model's value B = b0 + Σ b_j x_j and the residual y − B.
  std::vector<double> fitted_dph, residual_dph;
  std::optional<NearCollinearity> near_collinearity;  // terms poorly determined alone (absent: none)
  // The record's noise, identified by REML on this model's residual (absent
  // when the record has too few windows); ols's intervals come from it.
  std::shared_ptr<const NoiseContext> noise;
  RecordSupport support;  // what the record can tell these terms
  std::vector<LagSensitivity> lag_sensitivity;  // rate and gradient terms with intervals
  double ratio() const { return instability_before_dph / instability_after_dph; }
};

// The fit's warnings, worded (its JSON `warnings`, its text report's
// "warning:" lines): the nearly collinear terms.
std::vector<std::string> fit_warnings(const ModelFit& fit);

// Steps 4–6. Throws FitError for a design that cannot be fitted.
ModelFit fit_model(const PreparedData& data, const std::vector<const Term*>& terms,
                   const EngineInfo& engine, const EngineSettings& settings,
                   FitObserver* observer = nullptr);

// The fit every study takes as its reference: ols, with its default intervals
// (under the record's identified noise) unless `settings` choose others.
ModelFit reference_fit(const PreparedData& data, const std::vector<const Term*>& terms,
                       const EngineSettings& settings = {});

// The windows of a prepared record as the noise model sees them.
WindowGrid window_grid(const PreparedData& data);
// The noise of `problem`'s residual on the record's windows (nullptr: too few
// windows, or terms that cannot be told apart at the identification's block
// means; ols then falls back to Newey–West and says so).
std::shared_ptr<const NoiseContext> identify_record_noise(const PreparedData& data,
                                                          const LinearProblem& problem);

// Variable projection only: the parameters minimising the least-squares σ.
std::vector<double> fit_parameters(const DerivedSeries& derived, const std::vector<double>& y,
                                   const std::vector<const Term*>& terms);

// The model's value B = b0 + Σ b_j x_j at every window.
std::vector<double> model_values(const Eigen::MatrixXd& design, const Coefficients& c);

}  // namespace gyrotherm::fit
