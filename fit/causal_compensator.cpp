#include "fit/causal_compensator.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

#include "fit/data/derivatives.h"
#include "fit/model/terms.h"
#include "fit/pipeline.h"

namespace gyrotherm::fit {
namespace {

// The windows a closed window's row reads: itself and the two before it
// (fit/data/derivatives.cpp's backward differences; the class comment).
constexpr std::size_t kReach = 3;

// Windows [from, to) of a series, every per-window column with them.
AveragedSeries windows(const AveragedSeries& s, std::size_t from, std::size_t to) {
  AveragedSeries out;
  out.window_s = s.window_s;
  out.start_time_s = s.start_time_s;
  const auto cut = [from, to](const auto& v) {
    std::decay_t<decltype(v)> part;
    if (!v.empty()) part.assign(v.begin() + static_cast<std::ptrdiff_t>(from), v.begin() + static_cast<std::ptrdiff_t>(to));
    return part;
  };
  for (auto column : {&AveragedSeries::time_s, &AveragedSeries::temp_c, &AveragedSeries::gyro_dph,
                      &AveragedSeries::temp2_c, &AveragedSeries::gyro_sd_dph, &AveragedSeries::gyro_lag1,
                      &AveragedSeries::temp_rate_c_per_s, &AveragedSeries::temp2_rate_c_per_s,
                      &AveragedSeries::temp_rate_se, &AveragedSeries::temp2_rate_se})
    out.*column = cut(s.*column);
  for (auto column : {&AveragedSeries::samples, &AveragedSeries::run}) out.*column = cut(s.*column);
  for (const auto& [name, values] : s.extra) out.extra[name] = cut(values);
  for (const auto& [name, values] : s.extra_rate) out.extra_rate[name] = cut(values);
  for (const auto& [name, values] : s.extra_rate_se) out.extra_rate_se[name] = cut(values);
  return out;
}

}  // namespace

CausalCompensator::CausalCompensator(const SavedFit& fit, const CausalSettings& settings,
                                     std::vector<std::string> extra_names)
    : fit_(fit),
      settings_(settings),
      extra_names_(extra_names),
      averager_(fit.pipeline.averaging, settings.sample_interval_s, true, settings.bursts, std::move(extra_names)),
      glitches_(HampelRule{fit.pipeline.outliers.threshold, settings.outlier_floor_dph}, fit.pipeline.outliers.window_s),
      state_(fit.terms.size(), 0.0) {}

double CausalCompensator::bias_of(const AveragedSeries& windows, bool carry) {
  const DerivedSeries derived = derive(windows, DerivativeMode::causal, fit_.pipeline.derivative_span_s, fit_.pipeline.sensor_tau_s);
  Eigen::MatrixXd x = settings_.hold_c ? design_matrix_held(derived, fit_.terms, fit_.parameters,
                                                            settings_.hold_c->first, settings_.hold_c->second)
                                       : design_matrix(derived, fit_.terms, fit_.parameters);
  const Eigen::Index last = x.rows() - 1;
  for (std::size_t j = 0; j < fit_.terms.size(); ++j) {
    const Term& term = *fit_.terms[j];
    if (!term.next) continue;
    const auto col = static_cast<Eigen::Index>(j);
    if (carry && last > 0) {
      // Held as design_matrix_held holds it: the temperatures within the range.
      std::optional<DerivedSeries> held;
      if (settings_.hold_c && reads_temperature_level(&term))
        held = held_within(derived, settings_.hold_c->first, settings_.hold_c->second);
      x(last, col) = term.next(held ? *held : derived, static_cast<std::size_t>(last), fit_.parameters[j], state_[j]);
    }
    if (carry) state_[j] = x(last, col);
  }
  return model_values(x, fit_.coefficients).back();
}

double CausalCompensator::update(double t, double temp, double temp2, double gyro, std::span<const double> extra,
                                 bool* glitch) {
  if (!started_) {
    started_ = true;
    start_time_s_ = t;
  }
  const bool rejected = fit_.pipeline.remove_outliers && glitches_.is_glitch(t, gyro);
  if (glitch) *glitch = rejected;
  averager_.add(t, temp, gyro, temp2, !rejected, extra);
  const AveragedSeries& closed = averager_.closed();
  while (window_bias_.size() < closed.size()) {
    // The next window not yet given a bias, and the two before it.
    const std::size_t upto = window_bias_.size() + 1;
    window_bias_.push_back(bias_of(windows(closed, upto - std::min(upto, kReach), upto), true));
  }
  if (!window_bias_.empty()) return window_bias_.back();
  // Before any window closes: this sample as a window of its own.
  AveragedSeries own;
  own.start_time_s = start_time_s_;
  own.time_s = {t};
  own.temp_c = {temp};
  own.gyro_dph = {gyro};
  own.temp2_c = {temp2};
  own.samples = {1};
  own.run = {0};
  for (std::size_t i = 0; i < extra_names_.size() && i < extra.size(); ++i) own.extra[extra_names_[i]] = {extra[i]};
  return bias_of(own, false);
}

}  // namespace gyrotherm::fit
