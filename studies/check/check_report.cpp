// `gyrotherm check`'s renderers: the JSON (the numbers and enums of
// CheckResult) and the text, the only place its sentences are composed.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "studies/check/check_run.h"

namespace gyrotherm::studies {

namespace {

// "2490378 (instance 1), 2621450 (instance 0)" or "INS_GYR1_ID 2490378".
std::string devices_text(const std::vector<LogDevice>& devices) {
  std::string out;
  for (const LogDevice& d : devices)
    out += (out.empty() ? "" : ", ") + (d.parameter.empty() ? fmt::format("{} (instance {})", d.device_id, d.instance)
                                                           : fmt::format("{} {}", d.parameter, d.device_id));
  return out;
}

std::string rule_text(const CheckResult& r) {
  if (r.format == ParameterFormat::fit) return "the fit's model as `compensate` applies it, held at the fitted range's edge";
  if (r.format == ParameterFormat::px4)
    return "PX4's rule: offsets recomputed once a second, re-applied after a change of more than 1 °C, the temperature "
           "held within TMIN..TMAX";
  if (!r.sensor->is_gyro)  // its offsets are its calibration's, at INS_ACCn_CALTEMP: the log's start stands for it
    return fmt::format("ArduPilot's rule: every sample, the temperature held within TMIN..TMAX, relative to the {}'s "
                       "calibration temperature (taken as the log's first {:g} s, at {:.1f} °C)",
                       r.sensor->noun, r.request.boot_s, r.boot_c);
  return fmt::format("ArduPilot's rule: every sample, the temperature held within TMIN..TMAX, gyro offsets taken at boot "
                     "(the log's first {:g} s, at {:.1f} °C)",
                     r.request.boot_s, r.boot_c);
}

std::string finding_text(const CheckFinding& f, const CheckResult& r) {
  switch (f.issue) {
    case CheckIssue::calibration_span_minimum:
    case CheckIssue::calibration_span_advice: {
      const bool minimum = f.issue == CheckIssue::calibration_span_minimum;
      if (r.format != ParameterFormat::ardupilot)  // ArduPilot's limits are its own; the physics holds for every file
        return fmt::format("the calibration covers {:.1f} °C ({:.1f}..{:.1f} °C), under {:g} °C: {}", f.value, r.tmin_c,
                           r.tmax_c, f.limit,
                           minimum ? "its polynomial is fitted on a few degrees and says little of the curve outside them"
                                   : "a flight outside it runs on the edge's value");
      return fmt::format("the calibration covers {:.1f} °C ({:.1f}..{:.1f} °C), under the {:g} °C {}", f.value, r.tmin_c,
                         r.tmax_c, f.limit,
                         minimum ? "ArduPilot requires for a temperature calibration: its polynomial says little of "
                                   "the curve beyond a few degrees"
                                 : "ArduPilot advises: a flight outside it runs on the edge's value");
    }
    case CheckIssue::log_span_minimum:
      return fmt::format("this log spans {:.1f} °C only: it checks the calibration there, not its curve", f.value);
    case CheckIssue::temperature_quantised:
      return "the log's temperature is in whole degrees (as some Bosch parts report it): a calibration from it, or "
             "PX4's 1 °C hysteresis on it, corrects in steps";
    case CheckIssue::moving:
      return fmt::format("the vehicle moved: {:.1f} % of the samples show it ({}; a thermal check needs the {} at "
                         "rest), so the {} include the motion",
                         100.0 * f.value, f.name == "gyro" ? "rates above 10 °/s" : "the accelerometer's magnitude or direction changing",
                         r.sensor->noun, r.sensor->is_gyro ? "rates" : "readings");
    case CheckIssue::already_enabled:
      return fmt::format("the log was written with {} = {:g}: its rates are already corrected, and applying the "
                         "calibration again corrects twice",
                         f.name, f.value);
    case CheckIssue::device_mismatch:
      if (f.value == 0.0)
        return fmt::format("the calibration gives no device id ({} is 0 or absent): PX4 applies a set only to the {} "
                           "whose device id it names (export --device-id, the {}'s {}{{n}}_ID)",
                           f.name, r.sensor->noun, r.sensor->noun, r.sensor->px4_calibration);
      return fmt::format("the calibration is for device id {:.0f}, which is no {} of this log ({}): the firmware "
                         "would not apply it",
                         f.value, r.sensor->noun, devices_text(f.devices));
    case CheckIssue::outside_range:
      return fmt::format("{:.1f} % of the samples lie more than 0.1 °C outside the calibrated {:.1f}..{:.1f} °C, where "
                         "the correction is held at the edge",
                         100.0 * f.value, r.tmin_c, r.tmax_c);
    case CheckIssue::residual_over_limit:
      return fmt::format("axis {}: the residual {:.4g} {} exceeds the limit {:.4g} {}", f.name, f.value, r.sensor->unit,
                         f.limit, r.sensor->unit);
    case CheckIssue::no_residual:
      return fmt::format("axis {}: no {:g} °C temperature bin holds the {:.0f} samples a residual needs: this log cannot "
                         "show the residual against temperature{}",
                         f.name, f.limit, f.value, r.limit_dph ? ", so it does not pass --max-residual" : "");
    case CheckIssue::made_worse:
      return fmt::format("axis {}: the calibration leaves the instability at {:.2f} times the uncompensated log's: it "
                         "makes this log worse (another {}'s calibration, a sign or unit wrong?){}",
                         f.name, f.value, r.sensor->noun, r.limit_dph ? ", so it does not pass --max-residual" : "");
    case CheckIssue::little_gain:
      return fmt::format("axis {}: the calibration takes only {:.0f} % off the instability on this log: the log has "
                         "little thermal drift to remove (it spans {:.1f} °C), or the calibration does not fit this {}",
                         f.name, std::max(0.0, 100.0 * (1.0 - f.value)), r.log_temp_max_c - r.log_temp_min_c,
                         r.sensor->noun);
    case CheckIssue::calibration_caution:
      return fmt::format("the calibration file says: {}", f.name);
    case CheckIssue::fitted_log:
      return fmt::format("this log is the one the calibration was fitted on ({}, the same SHA-256): the residual is "
                         "the fit's own, and says nothing of how the calibration holds on another test; check it on "
                         "a second log",
                         f.name.empty() ? std::string("the fit file's data") : f.name);
  }
  return "";
}

}  // namespace

nlohmann::ordered_json check_json(const CheckResult& r) {
  nlohmann::ordered_json axes = nlohmann::ordered_json::array();
  for (const AxisCheck& x : r.axes) {
    nlohmann::ordered_json bins = nlohmann::ordered_json::array();
    for (const TemperatureBin& b : x.bins)
      bins.push_back({{"low_c", b.low_c}, {"high_c", b.high_c}, {"samples", b.samples}, {"mean_dph", b.mean_dph}});
    axes.push_back({{"axis", x.axis},
                    {"before_dph", x.before_dph},
                    {"after_dph", x.after_dph},
                    {"ratio", x.before_dph / x.after_dph},
                    {"offset_dph", x.offset_dph},
                    {"residual_dph", x.residual_dph},
                    {"residual_at_c", x.residual_at_c},
                    {"outside_share", x.outside_share},
                    {"bins", bins}});
  }
  nlohmann::ordered_json findings = nlohmann::ordered_json::array();
  for (const CheckFinding& f : r.findings) {
    nlohmann::ordered_json devices = nlohmann::ordered_json::array();
    for (const LogDevice& d : f.devices)
      devices.push_back({{"device_id", d.device_id},
                         {"instance", d.instance >= 0 ? nlohmann::ordered_json(d.instance) : nlohmann::ordered_json()},
                         {"parameter", d.parameter.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(d.parameter)}});
    findings.push_back({{"issue", check_issue_name(f.issue)}, {"value", f.value}, {"limit", f.limit},
                        {"name", f.devices.empty() ? f.name : devices_text(f.devices)}, {"devices", devices},
                        {"text", finding_text(f, r)}});
  }
  nlohmann::ordered_json out = {{"log", r.request.log},
                                {"log_format", r.log_format},
                                {"imu", r.log_instance >= 0 ? nlohmann::ordered_json(r.log_instance) : nullptr},
                                {"device_id", r.log_device_id},
                                {"parameters", r.request.parameters},
                                {"format", parameter_format_name(r.format)},
                                {"calibration", r.calibration},
                                {"temp_range_c", {r.tmin_c, r.tmax_c}},
                                {"boot_c", r.format == ParameterFormat::ardupilot ? nlohmann::ordered_json(r.boot_c) : nullptr},
                                {"samples", r.samples},
                                {"span_s", r.span_s},
                                {"log_temp_range_c", {r.log_temp_min_c, r.log_temp_max_c}},
                                {"window_s", r.window_s},
                                {"glitches_flagged", r.glitches_flagged},
                                {"bin_c", r.bin_c},
                                {"axes", axes},
                                {"findings", findings},
                                {"cautions", fit::caution_texts(r.cautions)},
                                {"max_residual_dph", r.limit_dph ? nlohmann::ordered_json(*r.limit_dph) : nullptr},
                                {"passed", r.passed ? nlohmann::ordered_json(*r.passed) : nullptr}};
  if (!r.sensor->is_gyro) {  // (a gyro's is as it was; the *_dph fields are in this unit)
    out["sensor"] = r.sensor->name;
    out["unit"] = r.sensor->unit;
  }
  return out;
}

std::string check_text(const CheckResult& r) {
  std::string out = fmt::format("check {} ({}{}) with {} ({} {}, {:.1f}..{:.1f} °C)\n", r.request.log, r.log_format,
                                r.log_instance >= 0 ? fmt::format(", {} instance {}, device {}", r.sensor->noun, r.log_instance, r.log_device_id) : "",
                                r.request.parameters, parameter_format_name(r.format), r.calibration, r.tmin_c, r.tmax_c);
  out += "  applied by " + rule_text(r) + "\n";
  out += fmt::format("  log: {} samples over {:.0f} s, {:.1f}..{:.1f} °C; instability = std of {:g} s means{}\n",
                     r.samples, r.span_s, r.log_temp_min_c, r.log_temp_max_c, r.window_s,
                     r.glitches_flagged == 0
                         ? std::string()
                         : fmt::format(" of every sample, the {} the fit's glitch rule flags too (compensate's "
                                       "figure leaves {} out, as a firmware cannot)",
                                       r.glitches_flagged, r.glitches_flagged == 1 ? "it" : "them"));
  const std::string_view unit = r.sensor->unit;
  out += fmt::format("  {:<8} {:>12} {:>12} {:>7} {:>11} {:>22} {:>9}\n", "axis", fmt::format("raw {}", unit),
                     fmt::format("comp. {}", unit), "ratio", fmt::format("offset {}", unit),
                     fmt::format("residual {} (at °C)", unit), "outside");
  const auto number = [](double v, const char* spec) { return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : "n/a"; };
  for (const AxisCheck& x : r.axes)
    out += fmt::format("  {:<8} {:>12} {:>12} {:>7} {:>11.4g} {:>13} ({:>5}) {:>8.1f}%\n", x.axis,
                       number(x.before_dph, "{:.5g}"), number(x.after_dph, "{:.5g}"),
                       number(x.before_dph / x.after_dph, "{:.2f}x"), x.offset_dph, number(x.residual_dph, "{:.4g}"),
                       number(x.residual_at_c, "{:.1f}"), 100.0 * x.outside_share);
  if (!r.axes.empty() && !std::isfinite(r.axes.front().before_dph))
    out += fmt::format("  (n/a: fewer than 3 windows of {:g} s in this log; --avg sets the window)\n", r.window_s);
  if (!r.axes.empty() && !r.axes.front().bins.empty()) {
    out += fmt::format("  residual against temperature (mean compensated − offset, {}, {:g} °C bins):\n", unit, r.bin_c);
    for (std::size_t b = 0; b < r.axes.front().bins.size(); ++b) {
      const TemperatureBin& bin = r.axes.front().bins[b];
      out += fmt::format("    {:6.1f}..{:<6.1f}", bin.low_c, bin.high_c);
      for (const AxisCheck& x : r.axes)
        for (const TemperatureBin& other : x.bins)
          if (other.low_c == bin.low_c) out += fmt::format(" {}={:<10.4g}", x.axis, other.mean_dph - x.offset_dph);
      out += "\n";
    }
  }
  for (const fit::UnitCaution& c : r.cautions) out += "caution: " + fit::caution_text(c) + "\n";
  for (const CheckFinding& f : r.findings) out += "finding: " + finding_text(f, r) + "\n";
  if (r.passed && *r.passed)
    out += fmt::format("verdict: PASS (every axis's residual against temperature within {:.4g} {})\n", *r.limit_dph, unit);
  else if (r.passed)
    out += fmt::format("verdict: FAIL (not every axis's residual against temperature is shown within {:.4g} {}: the "
                       "findings say which, or why this log cannot show it)\n",
                       *r.limit_dph, unit);
  return out;
}

}  // namespace gyrotherm::studies
