#include "studies/export/firmware_outcome.h"

#include "fit/data/plausibility.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "fit/compensation.h"
#include "fit/pipeline.h"

namespace gyrotherm::studies {
namespace {

// Holding the samples outside the fitted range at its edge is a cause of a
// cubic's cost where it costs more than this against not holding them.
constexpr double kEdgeCost = 1.05;
constexpr double kTooCostly = 1.2;  // the firmware's rule leaves more than 20 % above the model
constexpr float kPx4HysteresisC = 1.0f;
constexpr double kPx4PeriodS = 1.0;
constexpr float kArduPilotReference = 35.0f;

float clamped(float t, float lo, float hi) { return std::min(std::max(t, lo), hi); }

// What PX4's calc_thermal_offsets_3D (a barometer's _1D: X4, X5 too) gives
// for one axis at temperature t, in the base unit: float arithmetic in its
// order, t clamped to [tmin, tmax].
double px4_offset_dph(std::span<const float> x, float tref, float tmin, float tmax, float t, double per_base) {
  const float d = clamped(t, tmin, tmax) - tref, d2 = d * d, d3 = d2 * d;
  float offset = x[0] + x[1] * d + x[2] * d2 + x[3] * d3;
  if (x.size() > 4) {
    const float d4 = d3 * d, d5 = d4 * d;
    offset = offset + x[4] * d4 + x[5] * d5;
  }
  return static_cast<double>(offset) / per_base;
}

// The instability (std of the window averages, the fit's preparation) of
// the record's gyro less `subtracted`.
double instability_less(const fit::Measurement& m, const std::vector<double>& subtracted,
                        const fit::PipelineOptions& pipeline) {
  fit::Measurement rest = m;
  for (std::size_t i = 0; i < rest.size(); ++i) rest.gyro_dph[i] -= subtracted[i];
  return fit::instability_of(fit::prepare_data(rest, pipeline).series.gyro_dph);
}

}  // namespace

std::vector<double> px4_applied_dph(const std::vector<double>& time_s, const std::vector<double>& temp_c,
                                    std::span<const float> x, float tref, float tmin, float tmax, double per_base) {
  std::vector<double> out(time_s.size());
  if (time_s.empty()) return out;
  const double t0 = time_s.front();
  double applied = 0.0, next_run = t0;
  float last_published = 0.0f;
  bool published = false;
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    // A run of the module (every second from the first sample; runs in a gap
    // see the same sample): the first sample at or after its time.
    if (time_s[i] >= next_run) {
      const auto t = static_cast<float>(temp_c[i]);
      if (!published || std::fabs(t - last_published) > kPx4HysteresisC) {
        applied = px4_offset_dph(x, tref, tmin, tmax, t, per_base);
        last_published = t;
        published = true;
      }
      next_run = t0 + (std::floor((time_s[i] - t0) / kPx4PeriodS) + 1.0) * kPx4PeriodS;
    }
    out[i] = applied;
  }
  return out;
}

std::vector<double> ardupilot_applied_dph(const std::vector<double>& temp_c, const std::array<float, 3>& g,
                                          float tmin, float tmax, float boot_c, double bias_at_boot_dph,
                                          double per_base) {
  const auto p = [&](float t) {
    const float x = clamped(t, tmin, tmax) - kArduPilotReference;
    return (g[0] + (g[1] + g[2] * x) * x) * x * 1.0e-6f;
  };
  const float at_boot = p(boot_c);
  std::vector<double> out(temp_c.size());
  for (std::size_t i = 0; i < temp_c.size(); ++i)
    out[i] = static_cast<double>(p(static_cast<float>(temp_c[i])) - at_boot) / per_base + bias_at_boot_dph;
  return out;
}

FirmwareOutcome firmware_outcome(Firmware firmware, const FirmwareFile& file, const std::string& data_option,
                                 std::optional<double> boot_c, const fit::Table* data_table) {
  FirmwareOutcome o;
  o.firmware = firmware;
  o.kind = file.kind;
  const double per_base = firmware_per_base(*file.kind);
  const std::size_t n_x = static_cast<std::size_t>(file.kind->px4_order) + 1;
  const ExportRange& r = file.range;
  const auto tmin = static_cast<float>(r.tmin_c), tmax = static_cast<float>(r.tmax_c);
  const auto tref = static_cast<float>(r.tref_c);
  for (std::size_t i = 0; i < 3; ++i) {
    const AxisModel& a = file.axes[i];
    if (!a.present) continue;
    const FittedData data = fitted_data(*a.fit, data_option, data_table);
    if (!data.here()) {
      o.fit_file = a.fit->file.string();
      o.missing_data = a.fit->data_file;
      o.axes.clear();
      return o;
    }
    o.data = data.name;
    const fit::PipelineOptions pipeline = fit::reading_columns_of(a.fit->pipeline, a.fit->terms);
    const fit::Measurement m = data.read(pipeline.columns);
    // The record's units checked as fit checks them, each caution once: not
    // again where the fit recorded it (export words those, by channel).
    for (const fit::UnitCaution& c : fit::measurement_cautions(m)) {
      const std::string text = fit::caution_text(c);
      const auto worded_alike = [&](const RecordCaution& had) {
        return had.data == data.name && fit::caution_text(had.caution) == text;
      };
      const auto& recorded = a.fit->data_cautions;
      if (std::none_of(o.cautions.begin(), o.cautions.end(), worded_alike) &&
          std::find(recorded.begin(), recorded.end(), text) == recorded.end())
        o.cautions.push_back({data.name, c});
    }
    AxisOutcome out;
    out.axis = "XYZ"[i];
    out.channel = a.channel;
    out.model_dph = a.fit->instability_after_dph;
    out.before_dph = instability_less(m, std::vector<double>(m.size(), 0.0), pipeline);
    out.dropped = a.model.dropped;
    out.outside_share = static_cast<double>(std::count_if(m.temp_c.begin(), m.temp_c.end(), [&](double t) {
                          return t < r.tmin_c || t > r.tmax_c;
                        })) /
                        static_cast<double>(std::max<std::size_t>(m.size(), 1));
    std::vector<double> continuous(m.size()), unheld(m.size());  // the cubic held at the range's edge, and not
    if (firmware == Firmware::px4) {
      const std::array<float, kQuintic + 1> stored = px4_coefficients(a, tref, *file.kind);
      const std::span<const float> x(stored.data(), n_x);
      for (std::size_t k = 0; k < m.size(); ++k) {
        continuous[k] = px4_offset_dph(x, tref, tmin, tmax, static_cast<float>(m.temp_c[k]), per_base);
        unheld[k] = px4_offset_dph(x, tref, -1e9f, 1e9f, static_cast<float>(m.temp_c[k]), per_base);
      }
      out.exported_dph = instability_less(m, continuous, pipeline);
      out.firmware_dph =
          instability_less(m, px4_applied_dph(m.time_s, m.temp_c, x, tref, tmin, tmax, per_base), pipeline);
    } else {
      const float boot = static_cast<float>(boot_c.value_or(m.temp_c.front()));
      const std::array<float, 3> g = ardupilot_coefficients(a, *file.kind);
      const double bias_at_boot = a.model.evaluate(boot);  // what the boot offsets take out (the model's word)
      const std::vector<double> applied =
          ardupilot_applied_dph(m.temp_c, g, tmin, tmax, boot, bias_at_boot, per_base);
      for (std::size_t k = 0; k < m.size(); ++k) {
        continuous[k] = a.model.evaluate(std::clamp(m.temp_c[k], r.tmin_c, r.tmax_c));
        unheld[k] = a.model.evaluate(m.temp_c[k]);
      }
      out.exported_dph = instability_less(m, continuous, pipeline);
      out.firmware_dph = instability_less(m, applied, pipeline);
      out.boot_error_dph = a.model.evaluate(boot) - a.model.evaluate(std::clamp<double>(boot, r.tmin_c, r.tmax_c));
    }
    out.edge_costs = out.exported_dph > kEdgeCost * instability_less(m, unheld, pipeline);
    o.axes.push_back(out);
  }
  if (firmware == Firmware::ardupilot && !o.axes.empty()) {
    const double boot = boot_c.value_or(std::nan(""));
    if (boot_c && (boot < r.tmin_c || boot > r.tmax_c)) o.boot_outside_c = boot;
  }
  o.tmin_c = r.tmin_c;
  o.tmax_c = r.tmax_c;
  for (AxisOutcome& a : o.axes)
    if (!(a.firmware_dph <= kTooCostly * a.model_dph))  // (a NaN, of a record too short, counts as costly)
      a.cost = a.exported_dph > kTooCostly * a.model_dph ? FirmwareCost::exported_cubic
               : firmware == Firmware::px4               ? FirmwareCost::px4_step
                                                         : FirmwareCost::held_edge;
  return o;
}

void add_outcome(const FirmwareOutcome& outcome, ExportOutput* out) {
  for (const std::string& line : outcome.lines()) out->lines.push_back(line);
  for (const std::string& w : outcome.warnings()) out->warnings.push_back(w);
  out->json_fields.emplace_back("firmware_outcome", outcome.json().dump());
}

namespace {

// How the firmware applies the parameters, one line.
std::string firmware_rule_text(Firmware firmware, const fit::SensorKind& kind) {
  if (firmware == Firmware::px4)
    return "PX4 recomputes the offsets once a second and applies them only when the temperature has moved more than "
           "1 °C since the last applied";
  return kind.is_gyro ? "ArduPilot corrects every sample, relative to the gyro offsets taken at boot"
                      : fmt::format("ArduPilot corrects every sample, relative to the {} offsets of its calibration",
                                    kind.noun);
}

}  // namespace

nlohmann::ordered_json FirmwareOutcome::json() const {
  nlohmann::ordered_json j;
  j["data"] = data.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(data);
  j["rule"] = firmware_rule_text(firmware, *kind);
  j["axes"] = nlohmann::ordered_json::array();
  for (const AxisOutcome& a : axes)
    j["axes"].push_back({{"axis", std::string(1, a.axis)},
                         {"channel", a.channel},
                         {"instability_before_dph", a.before_dph},
                         {"model_dph", a.model_dph},
                         {"exported_dph", a.exported_dph},
                         {"firmware_dph", a.firmware_dph},
                         {"boot_error_dph", a.boot_error_dph}});
  j["notes"] = notes();
  return j;
}

namespace {

// Why the exported cubic itself costs: the terms it left out, the samples
// held at the fitted range's edge, or (neither) the cubic's own shape.
// `whole`: what applies the whole model at every sample ("--format c" for a
// gyro; another sensor's is applied by 'gyrotherm compensate').
std::string cubic_cost_text(const AxisOutcome& a, std::string_view polynomial, std::string_view whole) {
  const bool dropped = !a.dropped.empty(), outside = a.outside_share > 0.0 && a.edge_costs;
  const std::string terms = fmt::format("{}", fmt::join(a.dropped, ", "));
  if (dropped && !outside)
    return fmt::format("the exported {} already leaves this much: the terms it leaves out ({}) carry it; "
                       "{} compensates with them at every sample",
                       polynomial, terms, whole);
  if (outside && !dropped)
    return fmt::format("the exported {} already leaves this much: {:.0f} % of the samples lie outside the fitted "
                       "range, held at its edge; fit over the temperature range the vehicle will see",
                       polynomial, 100.0 * a.outside_share);
  if (dropped)
    return fmt::format("the exported {} already leaves this much: the terms it leaves out ({}) and the {:.0f} % "
                       "of the samples outside the fitted range (held at its edge); {} keeps the terms, a "
                       "fit over the range the vehicle will see the rest",
                       polynomial, terms, 100.0 * a.outside_share, whole);
  return fmt::format("the exported {} already leaves this much (a polynomial in T of at most {} order cannot follow "
                     "the fitted model): {} compensates with the model itself",
                     polynomial, polynomial == "cubic" ? "third" : "fifth", whole);
}

}  // namespace

std::vector<std::string> FirmwareOutcome::notes() const {
  const char* name = firmware == Firmware::px4 ? "PX4" : "ArduPilot";
  if (!fit_file.empty())  // the data is not here
    return {fmt::format("what {} will achieve is not predicted: the data {} was fitted on ('{}') is not here; give it "
                        "with --data",
                        name, fit_file, missing_data)};
  std::vector<std::string> out;
  for (const AxisOutcome& a : axes) {
    if (a.cost == FirmwareCost::none) continue;
    const std::string help =
        a.cost == FirmwareCost::exported_cubic
            ? cubic_cost_text(a, polynomial(), kind->is_gyro ? "--format c" : "'gyrotherm compensate'")
        : a.cost == FirmwareCost::px4_step
            ? fmt::format("the cost is PX4's 1 °C step, not the model: it grows with how fast the bias changes per "
                          "°C; a compensation applied at every sample{} avoids it",
                          kind->is_gyro ? " (--format c in your own code)" : "")
            : "samples outside the fitted range are held at its edge: fit over the temperature range the vehicle "
              "will see";
    out.push_back(fmt::format("{} ({}): as {} applies it {:.4g} {} against the model's {:.4g} ({:.2f}x): {}", a.axis,
                              a.channel, name, a.firmware_dph, kind->unit, a.model_dph, a.firmware_dph / a.model_dph,
                              help));
  }
  return out;
}

std::vector<std::string> FirmwareOutcome::warnings() const {
  std::vector<std::string> out;
  for (const RecordCaution& c : cautions) out.push_back(fmt::format("caution: {}: {}", c.data, fit::caution_text(c.caution)));
  if (boot_outside_c) {
    std::string errors;
    for (const AxisOutcome& a : axes)
      errors += fmt::format("{}{}: {:.4g}", errors.empty() ? "" : ", ", a.axis, a.boot_error_dph);
    out.push_back(fmt::format(
        "--boot-temp {:g} °C is outside the fitted range [{:.2f}, {:.2f}] °C: ArduPilot clamps it, and {} "
        "there keeps a constant error all flight ({} {}, by the model extrapolated); {} within the range, or fit "
        "over the temperatures the vehicle {} at",
        *boot_outside_c, tmin_c, tmax_c,
        kind->is_gyro ? std::string("a gyro calibrated at boot") : fmt::format("the {} calibrated", kind->noun),
        errors, kind->unit, kind->is_gyro ? "boot" : "calibrate", kind->is_gyro ? "boots" : "is calibrated"));
  }
  return out;
}

std::vector<std::string> FirmwareOutcome::lines() const {
  std::vector<std::string> out;
  if (!axes.empty()) {
    out.push_back(
        fmt::format("on {} (instability of the window averages, {}): {}", data, kind->unit,
                    firmware_rule_text(firmware, *kind)));
    for (const AxisOutcome& a : axes)
      out.push_back(fmt::format("  {} ({}): raw {:.4g}, model {:.4g}, exported {} {:.4g}, as the firmware applies it "
                                "{:.4g}",
                                a.axis, a.channel, a.before_dph, a.model_dph, polynomial(), a.exported_dph,
                                a.firmware_dph));
  }
  for (const std::string& n : notes()) out.push_back(n);
  return out;
}

}  // namespace gyrotherm::studies
