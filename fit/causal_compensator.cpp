#include "fit/causal_compensator.h"

#include <algorithm>
#include <cmath>

#include "fit/data/derivatives.h"
#include "fit/model/terms.h"
#include "fit/pipeline.h"

namespace gyrotherm::fit {

CausalCompensator::CausalCompensator(const SavedFit& fit, const CausalSettings& settings,
                                     std::vector<std::string> extra_names)
    : fit_(fit),
      settings_(settings),
      extra_names_(extra_names),
      averager_(fit.pipeline.averaging, settings.sample_interval_s, true, settings.bursts, std::move(extra_names)),
      glitches_(HampelRule{fit.pipeline.outliers.threshold, settings.outlier_floor_dph}, fit.pipeline.outliers.window_s) {}

double CausalCompensator::bias_of(const AveragedSeries& windows) const {
  const DerivedSeries derived = derive(windows, DerivativeMode::causal, fit_.pipeline.derivative_span_s, fit_.pipeline.sensor_tau_s);
  const Eigen::MatrixXd x = settings_.hold_c ? design_matrix_held(derived, fit_.terms, fit_.parameters,
                                                                  settings_.hold_c->first, settings_.hold_c->second)
                                             : design_matrix(derived, fit_.terms, fit_.parameters);
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
    // The windows up to the next one not yet given a bias.
    AveragedSeries prefix = closed;
    const std::size_t keep = window_bias_.size() + 1;
    prefix.time_s.resize(keep);
    prefix.temp_c.resize(keep);
    prefix.gyro_dph.resize(keep);
    if (!prefix.temp2_c.empty()) prefix.temp2_c.resize(keep);
    prefix.samples.resize(keep);
    prefix.run.resize(keep);
    for (auto& [name, values] : prefix.extra) values.resize(keep);
    // Edge rates are not read in causal mode (fit/data/derivatives.h); kept the windows' length.
    for (auto* v : {&prefix.temp_rate_c_per_s, &prefix.temp2_rate_c_per_s, &prefix.temp_rate_se, &prefix.temp2_rate_se})
      if (!v->empty()) v->resize(keep);
    for (auto* m : {&prefix.extra_rate, &prefix.extra_rate_se})
      for (auto& [name, values] : *m) values.resize(keep);
    window_bias_.push_back(bias_of(prefix));
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
  return bias_of(own);
}

}  // namespace gyrotherm::fit
