#include "fit/data/averaging.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "fit/data/median.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

bool is_gap(double step_s, double sample_interval_s, const AveragingOptions& o) {
  return step_s > o.gap_factor * sample_interval_s || step_s > o.window_s;
}

void AveragingOptions::validate() const {
  if (!(window_s > 0.0) || !std::isfinite(window_s))
    throw InputError(
        fmt::format("--avg {}: the averaging window must be a finite number of "
                    "seconds > 0",
                    window_s));
  if (!(gap_factor > 1.0) || !std::isfinite(gap_factor))
    throw InputError(
        fmt::format("gap_factor = {}: must be a finite number > 1 (a gap is a time "
                    "step longer than gap_factor sample intervals)",
                    gap_factor));
  if (!(min_fill > 0.0 && min_fill <= 1.0))
    throw InputError(
        fmt::format("min_fill = {}: must be in (0, 1] (the share of a window's "
                    "samples that must be valid)",
                    min_fill));
}

WindowAverager::WindowAverager(const AveragingOptions& options, double sample_interval_s,
                               bool has_temp2, bool whole_runs, std::vector<std::string> extra_names)
    : options_(options),
      has_temp2_(has_temp2),
      whole_runs_(whole_runs),
      extra_names_(std::move(extra_names)),
      sum_extra_(extra_names_.size(), 0.0),
      temp_edge_(EdgeRate::samples_for(options.window_s, sample_interval_s), sample_interval_s),
      temp2_edge_(temp_edge_),
      extra_edges_(extra_names_.size(), temp_edge_) {
  options_.validate();
  assert(sample_interval_s > 0.0);
  if (options_.window_s < sample_interval_s && !whole_runs_)
    throw InputError(
        fmt::format("--avg {}: the averaging window is shorter than the sample "
                    "interval ({} s)",
                    options_.window_s, sample_interval_s));
  min_valid_samples_ = options_.min_fill * options_.window_s / sample_interval_s;
  report_.sample_interval_s = sample_interval_s;
  report_.bursts = whole_runs_;
  series_.window_s = options_.window_s;
}

void WindowAverager::start_window(double time_s) {
  if (whole_runs_) {  // the window ends with the run
    window_end_s_ = std::numeric_limits<double>::infinity();
    return;
  }
  // The window [r + jW, r + (j+1)W) that holds time_s; j from a division, then
  // nudged so that rounding can never put time_s outside it.
  const double w = options_.window_s;
  double j = std::floor((time_s - run_start_s_) / w);
  while (run_start_s_ + (j + 1.0) * w <= time_s) j += 1.0;
  while (j > 0.0 && run_start_s_ + j * w > time_s) j -= 1.0;
  window_end_s_ = run_start_s_ + (j + 1.0) * w;
}

void WindowAverager::close_window() {
  if (window_samples_ == 0) return;
  const double needed = whole_runs_ ? options_.min_fill * static_cast<double>(window_samples_)
                                    : min_valid_samples_;
  if (window_valid_ > 0 && static_cast<double>(window_valid_) >= needed) {
    const auto n = static_cast<double>(window_valid_);
    series_.time_s.push_back(run_start_s_ + sum_time_s_ / n);
    series_.temp_c.push_back(sum_temp_c_ / n);
    series_.gyro_dph.push_back(sum_gyro_dph_ / n);
    if (has_temp2_) series_.temp2_c.push_back(sum_temp2_c_ / n);
    series_.samples.push_back(window_valid_);
    series_.run.push_back(run_);
    // Within the window: the sample variance, and the lag-1 autocorrelation
    // of consecutive valid samples about their own means.
    const double mean_u = sum_u_ / n;
    const double var = n > 1.0 ? std::max(0.0, (sum_u2_ - n * mean_u * mean_u) / (n - 1.0)) : 0.0;
    double lag1 = 0.0;
    if (lag_pairs_ >= 3 && var > 0.0) {
      const auto pairs = static_cast<double>(lag_pairs_);
      const double cov = (sum_lag_ - sum_lag_now_ * sum_lag_prev_ / pairs) / (pairs - 1.0);
      lag1 = std::clamp(cov / var, -1.0, 1.0);
    }
    series_.gyro_sd_dph.push_back(std::sqrt(var));
    series_.gyro_lag1.push_back(lag1);
    for (std::size_t i = 0; i < extra_names_.size(); ++i)
      series_.extra[extra_names_[i]].push_back(sum_extra_[i] / n);
    const double none = std::numeric_limits<double>::quiet_NaN();
    series_.temp_rate_c_per_s.push_back(whole_runs_ ? none : temp_edge_.rate());
    series_.temp_rate_se.push_back(whole_runs_ ? none : temp_edge_.standard_error());
    if (has_temp2_) {
      series_.temp2_rate_c_per_s.push_back(whole_runs_ ? none : temp2_edge_.rate());
      series_.temp2_rate_se.push_back(whole_runs_ ? none : temp2_edge_.standard_error());
    }
    for (std::size_t i = 0; i < extra_names_.size(); ++i) {
      series_.extra_rate[extra_names_[i]].push_back(whole_runs_ ? none : extra_edges_[i].rate());
      series_.extra_rate_se[extra_names_[i]].push_back(whole_runs_ ? none : extra_edges_[i].standard_error());
    }
  } else {
    ++report_.dropped_windows;
  }
  window_samples_ = window_valid_ = 0;
  sum_time_s_ = sum_temp_c_ = sum_gyro_dph_ = sum_temp2_c_ = 0.0;
  sum_u_ = sum_u2_ = sum_lag_ = sum_lag_now_ = sum_lag_prev_ = 0.0;
  std::fill(sum_extra_.begin(), sum_extra_.end(), 0.0);
  temp_edge_.reset();
  temp2_edge_.reset();
  for (EdgeRate& e : extra_edges_) e.reset();
  previous_valid_ = false;
  lag_pairs_ = 0;
}

void WindowAverager::add(double time_s, double temp_c, double gyro_dph, double temp2_c,
                         bool valid, std::span<const double> extra) {
  if (!started_) {
    started_ = true;
    series_.start_time_s = run_start_s_ = time_s;
    start_window(time_s);
  } else {
    assert(time_s > last_time_s_);
    const double step_s = time_s - last_time_s_;
    if (is_gap(step_s, report_.sample_interval_s, options_)) {
      close_window();
      longest_run_s_ = std::max(longest_run_s_, last_time_s_ - run_start_s_);
      report_.gaps.push_back({last_time_s_, time_s});
      ++run_;
      run_start_s_ = time_s;
      start_window(time_s);
    } else if (time_s >= window_end_s_) {
      close_window();
      start_window(time_s);
    }
  }
  last_time_s_ = time_s;
  ++window_samples_;
  if (!valid) {
    previous_valid_ = false;
    return;
  }
  if (window_valid_ == 0) first_gyro_ = gyro_dph;
  const double u = gyro_dph - first_gyro_;
  sum_u_ += u;
  sum_u2_ += u * u;
  if (previous_valid_) {
    sum_lag_ += u * previous_u_;
    sum_lag_now_ += u;
    sum_lag_prev_ += previous_u_;
    ++lag_pairs_;
  }
  previous_u_ = u;
  previous_valid_ = true;
  ++window_valid_;
  sum_time_s_ += time_s - run_start_s_;  // relative: epoch times keep their digits
  sum_temp_c_ += temp_c;
  sum_gyro_dph_ += gyro_dph;
  if (has_temp2_) sum_temp2_c_ += temp2_c;
  for (std::size_t i = 0; i < sum_extra_.size() && i < extra.size(); ++i) sum_extra_[i] += extra[i];
  if (!whole_runs_) {
    const double t = time_s - run_start_s_;
    temp_edge_.add(t, temp_c);
    if (has_temp2_) temp2_edge_.add(t, temp2_c);
    for (std::size_t i = 0; i < extra_edges_.size() && i < extra.size(); ++i) extra_edges_[i].add(t, extra[i]);
  }
}

AveragedSeries WindowAverager::finish() {
  close_window();
  if (!started_) return std::move(series_);
  longest_run_s_ = std::max(longest_run_s_, last_time_s_ - run_start_s_);
  // The gap-free runs, from the gaps: lengths (first to last sample, plus Δ)
  // and start times.
  const double interval_s = report_.sample_interval_s;
  std::vector<double> lengths, starts = {series_.start_time_s};
  for (const Gap& g : report_.gaps) {
    lengths.push_back(g.from_s - starts.back() + interval_s);
    starts.push_back(g.to_s);
  }
  lengths.push_back(last_time_s_ - starts.back() + interval_s);
  report_.median_run_s = median_of(lengths);
  if (whole_runs_) {
    std::vector<double> spacing;
    for (std::size_t i = 1; i < starts.size(); ++i) spacing.push_back(starts[i] - starts[i - 1]);
    report_.median_spacing_s = spacing.empty() ? 0.0 : median_of(std::move(spacing));
    series_.window_s = report_.median_run_s;
  }
  return std::move(series_);
}

bool in_bursts(const std::vector<double>& time_s, double sample_interval_s, const AveragingOptions& options) {
  const auto runs = gap_free_runs(time_s, sample_interval_s, options);
  std::vector<double> lengths;
  for (const auto& [first, last] : runs) lengths.push_back(time_s[last] - time_s[first] + sample_interval_s);
  return runs.size() > 1 && median_of(std::move(lengths)) < options.window_s;
}

double median_sample_interval_s(const std::vector<double>& time_s) {
  assert(time_s.size() >= 2);
  std::vector<double> steps(time_s.size() - 1);
  for (std::size_t k = 1; k < time_s.size(); ++k) steps[k - 1] = time_s[k] - time_s[k - 1];
  return median_of(std::move(steps));
}

std::vector<std::pair<std::size_t, std::size_t>> gap_free_runs(const std::vector<double>& time_s,
                                                               double sample_interval_s,
                                                               const AveragingOptions& options) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  if (time_s.empty()) return runs;
  std::size_t first = 0;
  for (std::size_t k = 1; k < time_s.size(); ++k)
    if (is_gap(time_s[k] - time_s[k - 1], sample_interval_s, options)) {
      runs.emplace_back(first, k - 1);
      first = k;
    }
  runs.emplace_back(first, time_s.size() - 1);
  return runs;
}

AveragedSeries average_windows(const Measurement& m, const std::vector<unsigned char>& valid,
                               const AveragingOptions& options, AveragingReport* report) {
  options.validate();
  assert(valid.size() == m.size());
  if (m.size() < 2)
    throw InputError(located(m.file, 0,
                             fmt::format("{} sample{}: averaging needs at least 2", m.size(),
                                         m.size() == 1 ? "" : "s")));
  const double interval_s = median_sample_interval_s(m.time_s);
  const bool bursts = in_bursts(m.time_s, interval_s, options);
  std::optional<WindowAverager> averager;
  try {
    std::vector<std::string> names;
    for (const auto& [name, values] : m.extra) names.push_back(name);
    averager.emplace(options, interval_s, m.has_temp2(), bursts, std::move(names));
  } catch (const InputError& e) {
    throw InputError(located(m.file, 0, e.what()));
  }
  std::vector<const std::vector<double>*> extra_columns;
  for (const auto& [name, values] : m.extra) extra_columns.push_back(&values);
  std::vector<double> extra(extra_columns.size());
  for (std::size_t k = 0; k < m.size(); ++k) {
    for (std::size_t i = 0; i < extra.size(); ++i) extra[i] = (*extra_columns[i])[k];
    averager->add(m.time_s[k], m.temp_c[k], m.gyro_dph[k], m.has_temp2() ? m.temp2_c[k] : 0.0,
                  valid[k] != 0, extra);
  }
  AveragedSeries series = averager->finish();
  if (report != nullptr) *report = averager->report();
  check_windows_survive(m.file, series, *averager, options);
  return series;
}

void check_windows_survive(const std::string& file, const AveragedSeries& series,
                           const WindowAverager& averager, const AveragingOptions& options) {
  if (series.size() > 0) return;
  throw InputError(located(
      file, 0,
      fmt::format("no averaging window survives: the record is {} s long (longest gap-free run "
                  "{} s, {} gap{}) and the window (--avg) is {} s, of which at least {} % must "
                  "be valid samples",
                  human(averager.record_s()), human(averager.longest_run_s()), averager.report().gaps.size(),
                  averager.report().gaps.size() == 1 ? "" : "s", human(options.window_s),
                  human(100.0 * options.min_fill))));
}

}  // namespace gyrotherm::fit
