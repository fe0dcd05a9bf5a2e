#include "studies/check/check_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include <nlohmann/json.hpp>

#include "fit/channels.h"
#include "fit/compensation.h"
#include "fit/data/autopilot_log.h"
#include "fit/data/plausibility.h"
#include "fit/data/units.h"
#include "sim/util/input_error.h"
#include "sim/util/sha256.h"
#include "studies/export/firmware.h"
#include "studies/export/firmware_outcome.h"
#include "studies/fit/compensate_run.h"

namespace gyrotherm::studies {

namespace {

// A caution the report has not yet worded (the axes of one log often share one).
void add_caution(CheckResult& r, const fit::UnitCaution& c) {
  const std::string text = fit::caution_text(c);
  for (const fit::UnitCaution& had : r.cautions)
    if (fit::caution_text(had) == text) return;
  r.cautions.push_back(c);
}

constexpr double kSpanMinimumC = kArduPilotSpanMinimumC;  // ArduPilot's minimum span for a temperature calibration
constexpr double kSpanAdviceC = 25.0;   // and its advice
constexpr std::size_t kBinSamples = 10; // a temperature bin needs this many samples to be shown
constexpr int kMaxBins = 20;
// A sample counts as outside TMIN..TMAX beyond this: the range's ends are
// window means, and a soak at an end reads on both sides of its mean by the
// sensor's noise, where the edge's correction differs from the curve's by a
// negligible slope × 0.1 °C.
constexpr double kOutsideMarginC = 0.1;

// The log as applied: one time and temperature, and per axis the rate and
// what the calibration subtracts (°/h).
struct Applied {
  std::vector<double> time_s, temp_c;
  std::vector<std::string> axis;
  std::vector<std::vector<double>> raw_dph, subtracted_dph;
  fit::LogContents contents;  // an autopilot log's; empty for a CSV
  std::optional<GyroCalibration> calibration;  // the firmware set applied (none for a fit file)
};

constexpr char kAxisNames[3] = {'X', 'Y', 'Z'};
// X, Y, Z; a one-channel sensor's as its log names it (a barometer's "pressure").
std::string axis_name(const fit::SensorKind& kind, std::size_t k) {
  return kind.axes() == 1 ? std::string(kind.log_columns) : std::string(1, kAxisNames[k]);
}

// The log's gyro to check and the calibration for it, as the firmware pairs
// them: PX4 by device id, ArduPilot by instance; --imu overrides the log's side.
std::pair<int, std::size_t> pair_gyro(const CheckRequest& o, const fit::LogContents& contents,
                                      const std::vector<GyroCalibration>& cals) {
  for (std::size_t c = 0; c < cals.size(); ++c)
    for (const fit::LogSensor& g : contents.sensors) {
      const bool same = cals[c].format == ParameterFormat::px4
                            ? cals[c].device_id && g.device_id != 0 && *cals[c].device_id == static_cast<long long>(g.device_id)
                            : cals[c].instance == g.instance;
      if (same && (!o.columns.imu || *o.columns.imu == g.instance)) return {g.instance, c};
    }
  const int instance = o.columns.imu.value_or(contents.default_instance());
  for (std::size_t c = 0; c < cals.size(); ++c)
    if (cals[c].format == ParameterFormat::ardupilot && cals[c].instance == instance) return {instance, c};
  return {instance, 0};
}

void read_autopilot(const CheckRequest& o, const fit::LogFormat& format, const std::vector<GyroCalibration>& cals,
                    const fit::SensorKind& kind, Applied* a, CheckResult* r, std::size_t* cal) {
  const fit::AutopilotReader reader = format.read;
  a->contents = reader(o.log, -1, {}, kind);
  const auto [instance, chosen] = pair_gyro(o, a->contents, cals);
  if (instance < 0)
    throw InputError(fmt::format("{}: no {} has 2 samples with a temperature; the file holds: {}", o.log, kind.noun,
                                 a->contents.describe()));
  *cal = chosen;
  // The log's unit to the base unit (rad/s to °/h; a ULog's pressure in Pa or mbar).
  const double to_base = fit::find_unit(kind.quantity, a->contents.unit, "").factor;
  a->raw_dph.assign(kind.axes(), {});
  const auto take = [&](double t, double temp, double x, double y, double z) {
    if (!std::isfinite(temp)) return;
    a->time_s.push_back(t);
    a->temp_c.push_back(temp);
    const double values[3] = {x, y, z};
    for (std::size_t k = 0; k < a->raw_dph.size(); ++k) a->raw_dph[k].push_back(values[k] * to_base);
  };
  const fit::LogContents read = reader(o.log, instance, take, kind);
  r->log_format = read.format;
  r->log_instance = instance;
  for (const fit::LogSensor& g : read.sensors)
    if (g.instance == instance) r->log_device_id = g.device_id;
  for (std::size_t k = 0; k < kind.axes(); ++k) a->axis.push_back(axis_name(kind, k));
}

void read_csv(const CheckRequest& o, const fit::SensorKind& kind, Applied* a, CheckResult* r) {
  fit::ColumnMap columns = fit::ColumnMap().with(o.columns);
  columns.imu.reset();
  columns.units.sensor = kind.is_gyro ? std::string() : std::string(kind.name);
  // The gyro's three axes by their usual names; another sensor's by role.
  if (o.columns.gyro.empty()) columns.gyro = kind.is_gyro ? "gyro_x,gyro_y,gyro_z" : fit::columns_for(o.log, columns).gyro;
  const std::vector<std::string> gyros = fit::parse_channels(columns.gyro);
  if (gyros.size() > kind.axes())
    throw InputError(fmt::format("--gyro-col {}: {} columns; a calibration corrects the {}, name up to {}, in that order",
                                 columns.gyro, gyros.size(), kind.axes() == 1 ? "one channel" : "X, Y and Z axes",
                                 kind.axes() == 1 ? "one" : "three"));
  for (std::size_t k = 0; k < gyros.size(); ++k) {
    fit::ColumnMap one = columns;
    one.gyro = gyros[k];
    const fit::Measurement m = fit::read_measurement_csv(o.log, one);
    for (const fit::UnitCaution& c : fit::measurement_cautions(m)) add_caution(*r, c);
    if (k == 0) a->time_s = m.time_s, a->temp_c = m.temp_c;
    a->raw_dph.push_back(m.gyro_dph);
    a->axis.push_back(axis_name(kind, k));
  }
  r->log_format = "CSV";
}

// Mean raw rate and temperature over the boot calibration (the first boot_s).
std::pair<double, double> boot_means(const Applied& a, std::size_t axis, double boot_s) {
  double rate = 0.0, temp = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.time_s.size() && (n == 0 || a.time_s[i] - a.time_s.front() < boot_s); ++i, ++n) {
    rate += a.raw_dph[axis][i];
    temp += a.temp_c[i];
  }
  return {rate / static_cast<double>(n), temp / static_cast<double>(n)};
}

Applied apply_firmware(const CheckRequest& o, const ParameterFile& p, CheckResult* r) {
  const std::vector<GyroCalibration> cals = gyro_calibrations(p);
  const fit::SensorKind& kind = *p.kind;
  if (cals.empty())
    throw InputError(fmt::format("{}: no {} calibration set (only the enable switch?); expected {} parameters", p.file,
                                 kind.noun,
                                 p.format == ParameterFormat::px4
                                     ? fmt::format("{}{{n}}_X{{k}}{}", kind.px4_stem, kind.axes() == 1 ? "" : "_{axis}")
                                     : fmt::format("INS_TCAL{{n}}_{}{{k}}_{{axis}}", kind.ardupilot_group)));
  Applied a;
  std::size_t cal = 0;
  if (const fit::LogFormat* format = fit::log_format_of(o.log); format != nullptr) {
    read_autopilot(o, *format, cals, kind, &a, r, &cal);
  } else {
    read_csv(o, kind, &a, r);
    if (o.columns.imu)
      for (std::size_t c = 0; c < cals.size(); ++c)
        if (cals[c].instance == *o.columns.imu) cal = c;
  }
  const GyroCalibration& c = *(a.calibration = cals[cal]);
  r->calibration = c.prefix;
  r->tmin_c = c.tmin_c;
  r->tmax_c = c.tmax_c;
  a.subtracted_dph.resize(a.raw_dph.size());
  const double per_base = firmware_per_base(kind);
  for (std::size_t k = 0; k < a.raw_dph.size(); ++k) {
    if (!c.axes[k]) {
      a.subtracted_dph[k].assign(a.time_s.size(), 0.0);
      continue;
    }
    if (c.format == ParameterFormat::px4) {
      const std::span<const float> x(c.px4_x[k].data(), static_cast<std::size_t>(kind.px4_order + 1));
      a.subtracted_dph[k] = px4_applied_dph(a.time_s, a.temp_c, x, c.tref_c, static_cast<float>(c.tmin_c),
                                            static_cast<float>(c.tmax_c), per_base);
    } else {
      auto [bias, boot_c] = boot_means(a, k, o.boot_s);
      r->boot_c = boot_c;
      // A gyro's offsets are taken at every boot; an accelerometer's are its
      // calibration's (INS_ACCOFFS, not in this file), and gravity stays in.
      if (!kind.is_gyro) bias = 0.0;
      a.subtracted_dph[k] = ardupilot_applied_dph(a.temp_c, c.ap_g[k], static_cast<float>(c.tmin_c),
                                                  static_cast<float>(c.tmax_c), static_cast<float>(boot_c), bias,
                                                  per_base);
    }
  }
  return a;
}

Applied apply_fit(const CheckRequest& o, const ParameterFile& p, CheckResult* r) {
  CompensateRequest request;
  request.data = o.log;
  request.fit_file = p.file;
  request.fits = p.fits;
  request.columns = o.columns;
  const CompensateRun run = run_compensate(request);
  Applied a;
  r->calibration = p.file;
  r->log_format = "CSV";
  if (const fit::LogFormat* format = fit::log_format_of(o.log); format != nullptr) {
    a.contents = format->read(o.log, -1, {}, *p.kind);
    r->log_format = a.contents.format;
  }
  bool first = true;
  std::vector<bool> flagged;
  for (std::size_t k = 0; k < run.channels.size(); ++k) {
    const fit::Compensation& c = run.channels[k];
    const bool full = !c.time_s.empty();
    if (first) {
      a.time_s = full ? c.time_s : c.data.series.time_s;
      a.temp_c = full ? c.temp_c : c.data.series.temp_c;
      if (c.fit_range_c) r->tmin_c = c.fit_range_c->first, r->tmax_c = c.fit_range_c->second;
      first = false;
    }
    // A one-channel fit file names no channel: its gyro column then.
    a.axis.push_back(!run.fits[k].channel.empty() ? run.fits[k].channel : run.fits[k].pipeline.columns.gyro);
    for (const fit::UnitCaution& caution : c.data.cautions) add_caution(*r, caution);
    a.raw_dph.push_back(full ? c.gyro_dph : c.data.series.gyro_dph);
    a.subtracted_dph.push_back(full ? c.model_dph : c.window_model_dph);
    if (full) flagged.resize(c.outlier.size(), false);
    for (std::size_t i = 0; full && i < c.outlier.size(); ++i) flagged[i] = flagged[i] || c.outlier[i];
  }
  r->glitches_flagged = static_cast<std::size_t>(std::count(flagged.begin(), flagged.end(), true));
  return a;
}

// The share of the samples whose rate on any axis is beyond a gyro at rest's.
double moving_share(const Applied& a) {
  std::size_t moving = 0;
  for (std::size_t i = 0; i < a.time_s.size(); ++i)
    moving += std::any_of(a.raw_dph.begin(), a.raw_dph.end(),
                          [&](const std::vector<double>& axis) { return std::abs(axis[i]) > fit::kRestRateDph; });
  return a.time_s.empty() ? 0.0 : static_cast<double>(moving) / static_cast<double>(a.time_s.size());
}

// Means of consecutive windows of `w` seconds from the first sample (windows with 2 samples or more).
std::vector<double> window_means(const std::vector<double>& t, const std::vector<double>& v, double w) {
  std::vector<double> out;
  double sum = 0.0, current = -1.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double index = std::floor((t[i] - t.front()) / w);
    if (index != current) {
      if (n >= 2) out.push_back(sum / static_cast<double>(n));
      sum = 0.0, n = 0, current = index;
    }
    sum += v[i], ++n;
  }
  if (n >= 2) out.push_back(sum / static_cast<double>(n));
  return out;
}

AxisCheck judge_axis(const Applied& a, std::size_t k, const CheckResult& r) {
  AxisCheck x;
  x.axis = a.axis[k];
  std::vector<double> comp(a.time_s.size());
  for (std::size_t i = 0; i < comp.size(); ++i) comp[i] = a.raw_dph[k][i] - a.subtracted_dph[k][i];
  // Fewer than 3 windows give no instability (NaN: null in the JSON).
  const auto instability = [&](const std::vector<double>& v) {
    const std::vector<double> means = window_means(a.time_s, v, r.window_s);
    return means.size() < 3 ? NAN : fit::instability_of(means);
  };
  x.before_dph = instability(a.raw_dph[k]);
  x.after_dph = instability(comp);
  x.window_time_s = window_means(a.time_s, a.time_s, r.window_s);
  x.window_raw_dph = window_means(a.time_s, a.raw_dph[k], r.window_s);
  x.window_compensated_dph = window_means(a.time_s, comp, r.window_s);
  x.offset_dph = std::accumulate(comp.begin(), comp.end(), 0.0) / static_cast<double>(comp.size());
  const double low = std::floor(r.log_temp_min_c);
  const auto bins = static_cast<std::size_t>(std::floor((r.log_temp_max_c - low) / r.bin_c)) + 1;
  std::vector<double> sum(bins, 0.0);
  std::vector<std::size_t> count(bins, 0);
  std::size_t outside = 0;
  for (std::size_t i = 0; i < comp.size(); ++i) {
    const auto b = std::min(bins - 1, static_cast<std::size_t>(std::floor((a.temp_c[i] - low) / r.bin_c)));
    sum[b] += comp[i], ++count[b];
    outside += a.temp_c[i] < r.tmin_c - kOutsideMarginC || a.temp_c[i] > r.tmax_c + kOutsideMarginC ? 1 : 0;
  }
  for (std::size_t b = 0; b < bins; ++b) {
    if (count[b] < kBinSamples) continue;
    const TemperatureBin bin{low + static_cast<double>(b) * r.bin_c, low + static_cast<double>(b + 1) * r.bin_c, count[b],
                             sum[b] / static_cast<double>(count[b])};
    if (!(std::abs(bin.mean_dph - x.offset_dph) < x.residual_dph)) {  // the first bin, or a larger one
      x.residual_dph = std::abs(bin.mean_dph - x.offset_dph);
      x.residual_at_c = 0.5 * (bin.low_c + bin.high_c);
    }
    x.bins.push_back(bin);
  }
  x.outside_share = static_cast<double>(outside) / static_cast<double>(comp.size());
  return x;
}

std::string ardupilot_enable_name(int instance) { return ardupilot_prefix(instance + 1) + "ENABLE"; }

void add_log_findings(const Applied& a, CheckResult* r) {
  const fit::LogContents& log = a.contents;
  if (r->format == ParameterFormat::px4) {
    if (const auto on = log.parameters.find(fmt::format("{}_ENABLE", r->sensor->px4_stem));
        on != log.parameters.end() && on->second == 1.0)
      r->findings.push_back({CheckIssue::already_enabled, on->second, 0.0, on->first});
  } else if (r->format == ParameterFormat::ardupilot && r->log_instance >= 0 && r->log_instance < 5) {
    if (const auto on = log.parameters.find(ardupilot_enable_name(r->log_instance));
        on != log.parameters.end() && on->second == 1.0)
      r->findings.push_back({CheckIssue::already_enabled, on->second, 0.0, on->first});
  }
  double accel_share = 0.0;
  if (const fit::LogAccel* acc = log.accel(r->log_instance)) accel_share = acc->moving_share();
  const double gyro_share = r->sensor->is_gyro ? moving_share(a) : 0.0;  // a rate at rest is a gyro's
  if (gyro_share > fit::kMovingShare || accel_share > fit::kMovingShare)
    r->findings.push_back({CheckIssue::moving, std::max(gyro_share, accel_share), fit::kMovingShare,
                           gyro_share >= accel_share ? "gyro" : "accelerometer"});
}

void add_device_finding(const Applied& a, CheckResult* r) {
  const std::optional<GyroCalibration>& cal = a.calibration;
  if (!cal || r->log_instance < 0) return;
  // PX4 pairs a set with the gyro whose device id is TC_G{n}_ID: 0 or none pairs with no gyro.
  if (cal->format == ParameterFormat::px4 && (!cal->device_id || *cal->device_id == 0)) {
    r->findings.push_back({CheckIssue::device_mismatch, 0.0, 0.0, cal->prefix + "ID"});
    return;
  }
  if (!cal->device_id || *cal->device_id == 0) return;
  std::vector<LogDevice> devices;
  if (cal->format == ParameterFormat::px4) {
    for (const fit::LogSensor& g : a.contents.sensors)
      if (g.device_id != 0) devices.push_back({static_cast<long long>(g.device_id), g.instance, ""});
  } else {
    const std::string name = ardupilot_gyro_id_name(cal->instance, r->sensor->ardupilot_group);
    if (const auto id = a.contents.parameters.find(name); id != a.contents.parameters.end())
      devices.push_back({static_cast<long long>(id->second), -1, name});
  }
  const bool match = std::any_of(devices.begin(), devices.end(),
                                 [&](const LogDevice& d) { return d.device_id == *cal->device_id; });
  if (!devices.empty() && !match)
    r->findings.push_back({CheckIssue::device_mismatch, static_cast<double>(*cal->device_id), 0.0, "", devices});
}

void add_findings(const Applied& a, CheckResult* r) {
  const double span = r->tmax_c - r->tmin_c;
  if (span < kSpanMinimumC)
    r->findings.push_back({CheckIssue::calibration_span_minimum, span, kSpanMinimumC, r->calibration});
  else if (span < kSpanAdviceC)
    r->findings.push_back({CheckIssue::calibration_span_advice, span, kSpanAdviceC, r->calibration});
  if (r->log_temp_max_c - r->log_temp_min_c < kSpanMinimumC)
    r->findings.push_back({CheckIssue::log_span_minimum, r->log_temp_max_c - r->log_temp_min_c, kSpanMinimumC, ""});
  const auto whole = static_cast<std::size_t>(std::count_if(a.temp_c.begin(), a.temp_c.end(), [](double t) {
    return std::abs(t - std::round(t)) < 1e-6;
  }));
  if (r->log_temp_max_c > r->log_temp_min_c && static_cast<double>(whole) >= 0.99 * static_cast<double>(a.temp_c.size()))
    r->findings.push_back({CheckIssue::temperature_quantised, 1.0, 0.0, ""});
  add_log_findings(a, r);
  add_device_finding(a, r);
  double outside = 0.0;
  for (const AxisCheck& x : r->axes) outside = std::max(outside, x.outside_share);
  if (outside > 0.0) r->findings.push_back({CheckIssue::outside_range, outside, 0.0, ""});
  for (const AxisCheck& x : r->axes)
    if (std::isnan(x.residual_dph)) r->findings.push_back({CheckIssue::no_residual, static_cast<double>(kBinSamples), r->bin_c, x.axis});
  // What the calibration does to the instability (the windows' spread), beside the residual against temperature.
  for (const AxisCheck& x : r->axes) {
    const double left = x.after_dph / x.before_dph;
    if (!(x.before_dph > 0.0) || !std::isfinite(left)) continue;
    if (left > kMadeWorse)
      r->findings.push_back({CheckIssue::made_worse, left, kMadeWorse, x.axis});
    else if (left > kLittleGain)
      r->findings.push_back({CheckIssue::little_gain, left, kLittleGain, x.axis});
  }
  if (r->limit_dph) {
    // An axis whose residual cannot be shown does not pass: the log cannot say it is within the limit;
    // nor does one the calibration makes worse, nor any where this log cannot test the calibration.
    r->passed = std::none_of(r->findings.begin(), r->findings.end(),
                             [](const CheckFinding& f) { return blocks_a_pass(f.issue); });
    for (const AxisCheck& x : r->axes)
      if (!(x.residual_dph <= *r->limit_dph)) {
        r->passed = false;
        if (!std::isnan(x.residual_dph))
          r->findings.push_back({CheckIssue::residual_over_limit, x.residual_dph, *r->limit_dph, x.axis});
      }
  }
}

void check_request(const CheckRequest& o) {
  if (!(o.avg_s > 0.0)) throw InputError(fmt::format("--avg {}: expected a window of more than 0 s", o.avg_s));
  if (!(o.boot_s > 0.0)) throw InputError(fmt::format("--boot {}: expected more than 0 s", o.boot_s));
  if (o.max_residual && !(*o.max_residual > 0.0 && std::isfinite(*o.max_residual)))
    throw InputError(fmt::format("--max-residual {}: expected a limit of more than 0", *o.max_residual));
  if (o.columns.imu && *o.columns.imu < 0) throw InputError(fmt::format("--imu {}: expected an instance of 0 or more", *o.columns.imu));
}

}  // namespace

bool blocks_a_pass(CheckIssue issue) {
  switch (issue) {
    case CheckIssue::made_worse:       // worse than no calibration
    case CheckIssue::fitted_log:       // the fit's own residual, no second test
    case CheckIssue::moving:           // the rates hold the vehicle's motion, not only the gyro's bias
    case CheckIssue::already_enabled:  // the log's rates are corrected already: applied again, twice
    case CheckIssue::device_mismatch:  // the firmware would apply the set to another gyro, or none
      return true;
    default: return false;
  }
}

std::string_view check_issue_name(CheckIssue issue) {
  switch (issue) {
    case CheckIssue::calibration_span_minimum: return "calibration_span_minimum";
    case CheckIssue::calibration_span_advice: return "calibration_span_advice";
    case CheckIssue::log_span_minimum: return "log_span_minimum";
    case CheckIssue::temperature_quantised: return "temperature_quantised";
    case CheckIssue::moving: return "moving";
    case CheckIssue::already_enabled: return "already_enabled";
    case CheckIssue::device_mismatch: return "device_mismatch";
    case CheckIssue::outside_range: return "outside_range";
    case CheckIssue::residual_over_limit: return "residual_over_limit";
    case CheckIssue::fitted_log: return "fitted_log";
    case CheckIssue::no_residual: return "no_residual";
    case CheckIssue::made_worse: return "made_worse";
    case CheckIssue::little_gain: return "little_gain";
    case CheckIssue::calibration_caution: return "calibration_caution";
  }
  return "";
}

CheckResult run_check(const CheckRequest& o) {
  check_request(o);
  CheckResult r;
  r.request = o;
  const ParameterFile p = read_parameter_file(o.parameters, o.columns.units.sensor);
  r.format = p.format;
  r.sensor = p.kind;
  if (o.max_residual) {
    // In the sensor's base unit unless a unit of its own is given (a gyro's for a gyro only).
    const std::string unit = o.residual_unit.empty() ? std::string(fit::base_unit(p.kind->quantity)) : o.residual_unit;
    r.limit_dph = fit::find_unit(p.kind->quantity, unit, "--residual-unit").to_base(*o.max_residual);
  }
  const Applied a = p.format == ParameterFormat::fit ? apply_fit(o, p, &r) : apply_firmware(o, p, &r);
  if (a.time_s.size() < 2)
    throw InputError(fmt::format("{}: {} sample{} with a temperature; a check needs 2 or more", o.log, a.time_s.size(),
                                 a.time_s.size() == 1 ? "" : "s"));
  r.samples = a.time_s.size();
  r.span_s = a.time_s.back() - a.time_s.front();
  const auto [lo, hi] = std::minmax_element(a.temp_c.begin(), a.temp_c.end());
  r.log_temp_min_c = *lo;
  r.log_temp_max_c = *hi;
  // The window: --avg, or a tenth of a shorter log, but long enough for 2 samples.
  std::vector<double> steps(a.time_s.size() - 1);
  for (std::size_t i = 0; i + 1 < a.time_s.size(); ++i) steps[i] = a.time_s[i + 1] - a.time_s[i];
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  r.window_s = std::max(std::min(o.avg_s, r.span_s / 10.0), 2.0 * steps[steps.size() / 2]);
  r.bin_c = std::max(1.0, (r.log_temp_max_c - r.log_temp_min_c) / kMaxBins);
  for (std::size_t k = 0; k < a.axis.size(); ++k) r.axes.push_back(judge_axis(a, k, r));
  for (const std::string& caution : p.cautions) r.findings.push_back({CheckIssue::calibration_caution, 0.0, 0.0, caution});
  // The log the calibration was fitted on (a fit file's data, a firmware file's provenance), given again: its
  // residual is the fit's own, no second test.
  if (std::error_code ec; !p.fitted_sha256.empty() && std::filesystem::is_regular_file(o.log, ec) &&
                          sha256_file_hex(o.log) == p.fitted_sha256)
    r.findings.push_back({CheckIssue::fitted_log, 0.0, 0.0, p.fitted_file});
  add_findings(a, &r);
  return r;
}

}  // namespace gyrotherm::studies
