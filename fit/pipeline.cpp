#include "fit/pipeline.h"

#include <boost/math/tools/minima.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/model/formula.h"
#include "fit/engines/ols.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

void check_columns(const std::vector<const Term*>& terms, const PreparedData& data,
                   const ColumnMap& columns) {
  for (const Term* t : terms)
    if (t->needs_temp2() && !data.has_temp2())
      throw InputError(fmt::format(
          "{}: term '{}' ({}) needs the column '{}', a second temperature sensor on the far side "
          "of the gyro block; the file has none (map another column with --temp2-col)",
          data.file, t->name, t->meaning, columns.temp2));
  for (const Term* t : terms)
    if (is_column_term(t) && !data.derived.extra.contains(t->column))
      throw InputError(fmt::format("{}: term '{}' names the column '{}', which was not read as "
                                   "numbers (is it in the file, and all numbers?)",
                                   data.file, t->name, t->column));
}

PipelineOptions reading_columns_of(PipelineOptions options, const std::vector<const Term*>& terms) {
  for (const Term* t : terms) {
    if (!is_column_term(t)) continue;
    std::vector<std::string>& extra = options.columns.extra;
    if (std::find(extra.begin(), extra.end(), t->column) == extra.end()) extra.emplace_back(t->column);
  }
  return options;
}

std::vector<double> model_values(const Eigen::MatrixXd& design, const Coefficients& c) {
  std::vector<double> v(static_cast<std::size_t>(design.rows()), c.intercept);
  for (Eigen::Index p = 0; p < design.rows(); ++p)
    for (Eigen::Index j = 0; j < design.cols(); ++j)
      v[static_cast<std::size_t>(p)] += c.b[static_cast<std::size_t>(j)] * design(p, j);
  return v;
}

namespace {

// Least-squares σ at given parameters; +inf when the design cannot be fitted
// (a parameter that makes a regressor constant, say).
double least_squares_sigma(const DerivedSeries& derived, const Eigen::VectorXd& y,
                           const std::vector<const Term*>& terms,
                           const std::vector<double>& parameters) {
  try {
    const LinearProblem problem(design_matrix(derived, terms, parameters), y, term_names(terms));
    return problem.optimum_objective();
  } catch (const FitError&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The linearised intervals of the header comment: the parameters', and the
// coefficients' own, widened by the parameters' uncertainty.
struct LinearisedIntervals {
  std::vector<std::optional<Interval>> parameters;  // per term
  FitResult ols;  // on the augmented design; empty when no parameter took part
};

LinearisedIntervals linearised_intervals(const DerivedSeries& derived, const Eigen::VectorXd& y,
                                         const std::vector<const Term*>& terms,
                                         const std::vector<double>& parameters,
                                         const Coefficients& c,
                                         std::shared_ptr<const NoiseContext> noise,
                                         const Engine& engine) {
  LinearisedIntervals out;
  out.parameters.assign(terms.size(), std::nullopt);
  std::vector<std::size_t> nonlinear;
  for (std::size_t j = 0; j < terms.size(); ++j) {
    const auto& spec = terms[j]->parameter;
    // On (or within a grid step of) a bound the search may have stopped short.
    if (spec && spec->differentiable && parameters[j] > spec->lower * 1.001 &&
        parameters[j] < spec->upper / 1.001)
      nonlinear.push_back(j);
  }
  if (nonlinear.empty()) return out;
  const Eigen::MatrixXd x = design_matrix(derived, terms, parameters);
  Eigen::MatrixXd augmented(x.rows(), x.cols() + static_cast<Eigen::Index>(nonlinear.size()));
  augmented.leftCols(x.cols()) = x;
  std::vector<std::string> names = term_names(terms);
  constexpr double kStep = 1e-4;  // in ln θ
  for (std::size_t i = 0; i < nonlinear.size(); ++i) {
    const std::size_t j = nonlinear[i];
    std::vector<double> up = parameters, down = parameters;
    up[j] *= std::exp(kStep);
    down[j] *= std::exp(-kStep);
    const std::vector<const Term*> one = {terms[j]};
    const Eigen::MatrixXd hi = design_matrix(derived, one, {up[j]});
    const Eigen::MatrixXd lo = design_matrix(derived, one, {down[j]});
    augmented.col(x.cols() + static_cast<Eigen::Index>(i)) = c.b[j] * (hi - lo).col(0) / (2.0 * kStep);
    names.push_back("d ln " + std::string(terms[j]->parameter->name));
  }
  try {
    LinearProblem problem(augmented, y, names);
    if (noise) problem.attach_noise(noise);
    out.ols = engine.fit(problem);  // the engine that gave the intervals (ols), its options as given
    for (std::size_t i = 0; i < nonlinear.size(); ++i) {
      const Interval& d = out.ols.inference.intervals[static_cast<std::size_t>(x.cols()) + i];
      out.parameters[nonlinear[i]] = Interval{parameters[nonlinear[i]] * std::exp(d.lower),
                                              parameters[nonlinear[i]] * std::exp(d.upper)};
    }
  } catch (const FitError&) {
    // A column that vanishes or is collinear: no interval can be had.
  }
  return out;
}

}  // namespace

ModelFit reference_fit(const PreparedData& data, const std::vector<const Term*>& terms,
                       const EngineSettings& settings) {
  return fit_model(data, terms, find_engine("ols"), settings);
}

namespace {

// Rate terms (dT, T*dT, d2T, hyst) and the gradient: what a sensor's lag moves.
bool lag_moves(const Term& t) {
  return t.family == effects::Family::rate || t.needs_temp2();
}

std::vector<LagSensitivity> lag_sensitivity(const PreparedData& data, const ModelFit& fit) {
  std::vector<LagSensitivity> out;
  if (fit.engine.inference.intervals.size() != fit.terms.size() || data.series.size() < 3) return out;
  if (std::none_of(fit.terms.begin(), fit.terms.end(), [](const Term* t) { return lag_moves(*t); })) return out;
  constexpr double kProbeS = 10.0;
  const DerivedSeries delagged = derive(data.series, data.derivative, data.derivative_span_s, data.sensor_tau_s + kProbeS);
  const Eigen::VectorXd y =
      Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(), static_cast<Eigen::Index>(data.series.size()));
  // Least squares on both (whatever the fit's engine): the move is the lag's alone.
  const auto least_squares = [&](const DerivedSeries& d) {
    const LinearProblem problem(design_matrix(d, fit.terms, fit.parameters), y, term_names(fit.terms), Collinear::keep);
    return problem.physical(least_squares_optimum(problem));
  };
  Coefficients as_read, moved;
  try {
    as_read = least_squares(data.derived);
    moved = least_squares(delagged);
  } catch (const FitError&) {
    return out;
  }
  for (std::size_t k = 0; k < fit.terms.size(); ++k) {
    if (!lag_moves(*fit.terms[k])) continue;
    const Interval& interval = fit.engine.inference.intervals[k];
    const double half = 0.5 * (interval.upper - interval.lower);
    const double per_s = std::abs(moved.b[k] - as_read.b[k]) / kProbeS;
    out.push_back({k, per_s > 0.0 ? half / per_s : std::numeric_limits<double>::infinity()});
  }
  return out;
}

}  // namespace

WindowGrid window_grid(const PreparedData& data) {
  WindowGrid grid;
  grid.time_s = data.series.time_s;
  grid.window_s = data.series.window_s;
  const double dt = data.averaging.sample_interval_s;
  for (std::size_t i = 0; i < data.series.size(); ++i)
    grid.averaging_s.push_back(i < data.series.samples.size() && dt > 0.0
                                   ? static_cast<double>(data.series.samples[i]) * dt
                                   : grid.window_s);
  return grid;
}

std::shared_ptr<const NoiseContext> identify_record_noise(const PreparedData& data,
                                                          const LinearProblem& problem) {
  const WindowGrid grid = window_grid(data);
  if (grid.size() < problem.dimension() + 5 || !(grid.window_s > 0.0)) return nullptr;
  try {
    NoiseModel model = identify_noise(grid, problem.design(), problem.y());
    model.sensor = &data.units.kind();  // the components' names and units
    return std::make_shared<const NoiseContext>(NoiseContext{std::move(model), grid});
  } catch (const FitError&) {
    return nullptr;  // nothing to trust: ols falls back to Newey–West
  }
}

std::vector<double> fit_parameters(const DerivedSeries& derived, const std::vector<double>& y_in,
                                   const std::vector<const Term*>& terms) {
  std::vector<double> params = default_parameters(terms);
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(y_in.data(), static_cast<Eigen::Index>(y_in.size()));
  std::vector<std::size_t> nonlinear;
  for (std::size_t j = 0; j < terms.size(); ++j)
    if (terms[j]->parameter) nonlinear.push_back(j);
  if (nonlinear.empty()) return params;

  // Coordinate search: each parameter in turn over its bounds (log scale),
  // three rounds when there are several.
  const int rounds = nonlinear.size() > 1 ? 3 : 1;
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t j : nonlinear) {
      const TermParameter& spec = *terms[j]->parameter;
      const double lo = std::log(spec.lower), hi = std::log(spec.upper);
      auto sigma_at = [&](double log_value) {
        std::vector<double> p = params;
        p[j] = std::exp(log_value);
        return least_squares_sigma(derived, y, terms, p);
      };
      constexpr int kGrid = 41;
      double best_x = lo, best_f = std::numeric_limits<double>::infinity();
      for (int i = 0; i < kGrid; ++i) {
        const double x = lo + (hi - lo) * i / (kGrid - 1);
        const double f = sigma_at(x);
        if (f < best_f) {
          best_f = f;
          best_x = x;
        }
      }
      // Brent's method between the grid neighbours of the best point.
      const double step = (hi - lo) / (kGrid - 1);
      const auto [refined, f] =
          boost::math::tools::brent_find_minima(sigma_at, std::max(lo, best_x - step), std::min(hi, best_x + step), 30);
      params[j] = std::exp(f < best_f ? refined : best_x);
    }
  }
  return params;
}

std::vector<std::string> fit_warnings(const ModelFit& fit) {
  std::vector<std::string> out;
  if (fit.near_collinearity) out.push_back(near_collinearity_text(*fit.near_collinearity));
  return out;
}

ModelFit fit_model(const PreparedData& data, const std::vector<const Term*>& terms,
                   const EngineInfo& engine, const EngineSettings& settings,
                   FitObserver* observer) {
  ModelFit fit;
  fit.terms = terms;
  fit.parameters = fit_parameters(data.derived, data.series.gyro_dph, terms);
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(
      data.series.gyro_dph.data(), static_cast<Eigen::Index>(data.series.size()));
  LinearProblem problem(design_matrix(data.derived, terms, fit.parameters), y, term_names(terms));
  fit.support = record_support(data, terms);
  fit.noise = identify_record_noise(data, problem);
  if (fit.noise) problem.attach_noise(fit.noise);
  const std::unique_ptr<Engine> e = engine.make(settings);
  fit.engine = e->fit(problem, observer);
  fit.coefficients = problem.physical(fit.engine.z);
  fit.instability_before_dph = problem.sigma_y();
  fit.instability_after_dph = problem.sigma_two_pass(fit.coefficients);
  fit.optimum_dph = problem.sigma_two_pass(problem.physical(least_squares_optimum(problem)));
  fit.points = problem.points();
  fit.fitted_dph = model_values(problem.design(), fit.coefficients);
  fit.residual_dph.resize(fit.fitted_dph.size());
  for (std::size_t p = 0; p < fit.fitted_dph.size(); ++p) fit.residual_dph[p] = data.series.gyro_dph[p] - fit.fitted_dph[p];
  fit.near_collinearity = problem.near_collinearity();
  fit.parameter_intervals.assign(terms.size(), std::nullopt);
  if (!fit.engine.inference.intervals.empty()) {
    LinearisedIntervals li =
        linearised_intervals(data.derived, y, terms, fit.parameters, fit.coefficients, fit.noise, *e);
    fit.parameter_intervals = std::move(li.parameters);
    if (!li.ols.inference.intervals.empty()) {
      // The coefficients' intervals with the parameters' uncertainty in them.
      const TermInference& linearised = li.ols.inference;
      const auto n = static_cast<std::ptrdiff_t>(terms.size());
      TermInference& inference = fit.engine.inference;
      inference.intervals.assign(linearised.intervals.begin(), linearised.intervals.begin() + n);
      inference.p_values.assign(linearised.p_values.begin(), linearised.p_values.begin() + n);
      inference.interval_method = linearised.interval_method;
      inference.interval_method.linearised_parameters = true;
    }
  }
  fit.lag_sensitivity = lag_sensitivity(data, fit);
  return fit;
}

}  // namespace gyrotherm::fit
