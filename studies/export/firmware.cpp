#include "studies/export/firmware.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "fit/compensation.h"
#include "fit/data/sensor_kind.h"
#include "fit/data/units.h"
#include "fit/engines/engine.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/util/comma_list.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {
namespace {

// The best polynomial the firmware can express (up to `order`), refitted by
// least squares on the same windows: the highest power first, else
// (collinear on this record) one lower, down to the line; its instability, or
// NaN when none can be fitted.
std::pair<std::string, double> refitted_polynomial(const fit::PreparedData& data, int order) {
  static const char* const kModels[] = {"T + T^2 + T^3 + T^4 + T^5", "T + T^2 + T^3 + T^4", "T + T^2 + T^3",
                                        "T + T^2", "T"};
  for (const char* model : std::span(kModels).subspan(static_cast<std::size_t>(kQuintic - std::min(order, kQuintic)))) {
    try {
      fit::EngineSettings settings;
      settings.options["intervals"] = "model";  // only the σ is wanted
      return {model, fit::reference_fit(data, fit::parse_formula(model), settings).instability_after_dph};
    } catch (const FitError&) {
      continue;
    }
  }
  return {"", std::nan("")};
}

// With terms dropped: the instability of the fitted data with the whole
// model, with the cubic alone (the same coefficients, not refitted), and
// with the best polynomial the firmware can express (up to `order`, the one
// firmware_axes exports) refitted on that data.
std::string dropped_report(const fit::SavedFit& f, const PolynomialModel& cubic, int order, const ExportRequest& o,
                           DroppedCost* cost_out) {
  const FittedData data = fitted_data(f, o.data, o.data_table);
  if (!data.here())
    throw InputError(fmt::format("--drop-unsupported: the data {} was fitted on ('{}') is not here; give it with "
                                 "--data so that export can say how much dropping {} costs",
                                 f.file.string(), f.data_file, cubic.dropped.front()));
  const fit::PipelineOptions pipeline = fit::reading_columns_of(f.pipeline, f.terms);
  const fit::Measurement m = data.read(pipeline.columns);
  const DroppedCost cost = dropped_cost(f, cubic, m);
  *cost_out = cost;
  std::string names;
  for (const std::string& n : cubic.dropped) names += (names.empty() ? "" : ", ") + n;
  const fit::SensorKind& kind = f.pipeline.columns.units.kind();
  const auto [model, refitted] = refitted_polynomial(fit::prepare_data(m, pipeline), order);
  const std::string_view unit = kind.unit;
  // Another sensor's fit names its sensor and column again (a gyro's are the defaults).
  const std::string sensor_options =
      kind.is_gyro ? std::string() : fmt::format(" --sensor {} --gyro-col '{}'", kind.name, channel_name(f));
  const std::string refit =
      model.empty() ? "no polynomial in T can be fitted on this record"
                    : fmt::format("the best the firmware can express, B = b0 + {} refitted on the same data, leaves "
                                  "{:.6g} {}{} ({}, then export that fit)",
                                  model, refitted, unit,
                                  refitted < cost.without_dph ? "" : " (no better than these coefficients)",
                                  // Arrays have no file to name on a command line: a Python call.
                                  data.table != nullptr && kind.is_gyro
                                      ? fmt::format("gyrotherm.fit(data, model=\"{}\")", model)
                                      : fmt::format("gyrotherm fit {}{} --model '{}'", data.name, sensor_options, model));
  return fmt::format("{}: dropped {}: the instability on {} rises from {:.6g} to {:.6g} {} ({:.2f}x); {}",
                     channel_name(f), names, data.name, cost.with_dph, cost.without_dph, unit,
                     cost.without_dph / cost.with_dph, refit);
}

}  // namespace

FittedData fitted_data(const fit::SavedFit& f, const std::string& option, const fit::Table* table) {
  if (table != nullptr) return {table->name, table};
  if (!option.empty()) return {option};
  const std::filesystem::path named = f.data_file;
  if (named.empty()) return {};
  if (std::filesystem::exists(named)) return {named.string()};
  if (std::filesystem::exists(f.file.parent_path() / named)) return {(f.file.parent_path() / named).string()};
  return {};
}

fit::Measurement FittedData::read(const fit::ColumnMap& columns) const {
  return table != nullptr ? fit::read_table(*table, fit::for_table(columns)) : fit::read_measurement_csv(name, columns);
}

std::array<float, kQuintic + 1> px4_coefficients(const AxisModel& axis, float tref, const fit::SensorKind& kind) {
  std::array<float, kQuintic + 1> x{};
  if (!axis.present) return x;
  const double per_base = firmware_per_base(kind);
  const std::array<double, kQuintic + 1> a = reexpand(axis.model, tref);  // about the float TREF the firmware uses
  for (std::size_t k = kind.is_gyro ? 0 : 1; k < x.size(); ++k) x[k] = static_cast<float>(a[k] * per_base);
  return x;
}

std::array<float, 3> ardupilot_coefficients(const AxisModel& axis, const fit::SensorKind& kind) {
  std::array<float, 3> g{};
  if (!axis.present) return g;
  const double per_base = firmware_per_base(kind);
  const std::array<double, kQuintic + 1> a = reexpand(axis.model, kArduPilotReferenceC);
  for (std::size_t k = 1; k < 4; ++k) g[k - 1] = static_cast<float>(a[k] * per_base * 1e6);
  return g;
}

bool single_channel(const fit::SensorKind& kind) { return kind.axes() == 1; }

double firmware_per_base(const fit::SensorKind& kind) {
  return kind.is_gyro ? kRadPerSecPerDegPerHour : 1.0 / fit::find_unit(kind.quantity, kind.ulog.unit, "").factor;
}

const fit::SensorKind& exported_kind(const std::vector<fit::SavedFit>& fits) {
  const fit::SensorKind& kind = fits.front().pipeline.columns.units.kind();
  for (const fit::SavedFit& f : fits)
    if (&f.pipeline.columns.units.kind() != &kind)
      throw InputError(fmt::format("{}: its channels are fits of different sensors ({} and {}); a firmware file "
                                   "holds one sensor's",
                                   f.file.string(), kind.name, f.pipeline.columns.units.kind().name));
  return kind;
}

std::string ardupilot_prefix(int instance) {
  if (instance >= 1 && instance <= 3) return fmt::format("INS_TCAL{}_", instance);
  if (instance == 4 || instance == 5) return fmt::format("INS{}_TCAL_", instance);
  throw InputError(fmt::format("--instance {}: ArduPilot numbers its IMUs 1 to 5 (INS_TCAL1_ to INS_TCAL3_, "
                               "INS4_TCAL_, INS5_TCAL_)",
                               instance));
}

int px4_instance(const std::optional<int>& instance) {
  const int n = instance.value_or(0);
  if (n < 0 || n > 3)
    throw InputError(fmt::format("--instance {}: PX4 has the thermal compensation sets 0 to 3 of each sensor (TC_G0 "
                                 "to TC_G3 of the gyros, TC_A, TC_B, TC_M of the others)",
                                 n));
  return n;
}

long long px4_device_id(long long id) {
  // TC_G{n}_ID is an int32 parameter compared as uint32 with the device id.
  if (id < -2147483648LL || id > 4294967295LL)
    throw InputError(fmt::format("--device-id {}: a PX4 device id is a 32-bit number (0 to 4294967295, as "
                                 "CAL_GYRO{{n}}_ID, CAL_ACC{{n}}_ID, CAL_BARO{{n}}_ID or CAL_MAG{{n}}_ID shows it)",
                                 id));
  return id > 2147483647LL ? id - 4294967296LL : id;
}

std::string as_float(double v) { return fmt::format("{:.9g}", static_cast<float>(v)); }

std::string provenance(const ExportHeader& h, const char* comment) {
  std::string out = fmt::format(
      "{0} gyrotherm export: {6} thermal compensation from {1}\n"
      "{0}   fit file SHA-256 {2}\n"
      "{0}   engine {3}, model B = b0 + {4} ({7}, T in °C), exported {5}\n",
      comment, h.fit_file, h.fit_sha256, h.engine, h.model_text, h.date_utc, h.sensor, h.unit);
  if (!h.data_sha256.empty())
    out += fmt::format("{}   {}{}{}{}\n", comment, kFittedOn, h.data_file, kFittedSha, h.data_sha256);
  return out;
}

std::string axis_comment(const AxisModel& axis, std::string_view name, std::string_view firmware) {
  if (!axis.present) return fmt::format("#   axis {}: not compensated (zeros)\n", name);
  if (axis.model.dropped.empty()) return fmt::format("#   axis {}: {}\n", name, axis.channel);
  return fmt::format("#   axis {}: {}, without {} (--drop-unsupported: {} cannot express {})\n", name, axis.channel,
                     fmt::join(axis.model.dropped, ", "), firmware, axis.model.dropped.size() == 1 ? "it" : "them");
}

double PolynomialModel::evaluate(double t) const {
  return c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
}

PolynomialModel polynomial_of(const fit::SavedFit& fit, bool drop_unsupported, const std::string& format, int order) {
  PolynomialModel m;
  m.c[0] = fit.coefficients.intercept;
  std::vector<std::string> unsupported;
  for (std::size_t k = 0; k < fit.terms.size(); ++k) {
    const std::string name(fit.terms[k]->name);
    const int power = fit.terms[k]->temperature_power;  // 0: not a power of T
    if (power < 1 || power > order) {
      unsupported.push_back(name);
      continue;
    }
    m.c[static_cast<std::size_t>(power)] += fit.coefficients.b[k];
  }
  if (!unsupported.empty() && !drop_unsupported) {
    std::string names;
    for (const std::string& n : unsupported) names += (names.empty() ? "" : ", ") + n;
    throw InputError(fmt::format(
        "{}: the model has {} ({}), which {} cannot express: its {} thermal compensation is a {} in "
        "temperature. {}fit a polynomial (--model '{}'), or pass "
        "--drop-unsupported to leave {} out (export then prints how much the instability rises)",
        fit.file.string(), unsupported.size() == 1 ? "a term" : "terms", names, format,
        fit.pipeline.columns.units.kind().noun, order == kCubic ? "cubic" : "quintic",
        fit.pipeline.columns.units.kind().is_gyro ? "Use --format c for the whole model, "
                                                  : "Use 'gyrotherm compensate' for the whole model, ",
        order == kCubic ? "T + T^2 + T^3" : "T + T^2 + T^3 + T^4 + T^5", unsupported.size() == 1 ? "it" : "them"));
  }
  m.dropped = unsupported;
  return m;
}

DroppedCost dropped_cost(const fit::SavedFit& fit, const PolynomialModel& cubic, const fit::Measurement& data) {
  const fit::Compensation c = fit::compensate(data, fit, fit::reading_columns_of(fit.pipeline, fit.terms));
  std::vector<double> residual;
  for (std::size_t p = 0; p < c.data.series.size(); ++p)
    residual.push_back(c.data.series.gyro_dph[p] - cubic.evaluate(c.data.series.temp_c[p]));
  return {c.after_dph, fit::instability_of(residual)};
}

std::array<double, kQuintic + 1> reexpand(const PolynomialModel& m, double r) {
  // a_k = B⁽ᵏ⁾(r)/k!, each by Horner in r (a cubic's as before: the higher
  // terms add exact zeros).
  const auto& c = m.c;
  return {m.evaluate(r),
          c[1] + r * (2.0 * c[2] + r * (3.0 * c[3] + r * (4.0 * c[4] + r * (5.0 * c[5])))),
          c[2] + r * (3.0 * c[3] + r * (6.0 * c[4] + r * (10.0 * c[5]))),
          c[3] + r * (4.0 * c[4] + r * (10.0 * c[5])),
          c[4] + r * (5.0 * c[5]),
          c[5]};
}

ExportRange export_range(const std::array<AxisModel, 3>& axes) {
  ExportRange r{-1e300, 1e300, 0.0};
  bool any = false;
  for (const AxisModel& a : axes) {
    if (!a.present) continue;
    any = true;
    r.tmin_c = std::max(r.tmin_c, a.temp_min_c);
    r.tmax_c = std::min(r.tmax_c, a.temp_max_c);
  }
  if (!any) throw InputError("export: no axis has a fit (--axes names none of the fit's channels)");
  if (!(r.tmax_c > r.tmin_c))
    throw InputError(fmt::format("export: the axes' fitted temperature ranges do not overlap ({:.2f} to {:.2f} °C)",
                                 r.tmin_c, r.tmax_c));
  r.tref_c = 0.5 * (r.tmin_c + r.tmax_c);
  return r;
}

std::array<AxisModel, 3> firmware_axes(const ExportRequest& o, const std::vector<fit::SavedFit>& fits,
                                       const std::string& format, ExportOutput* out) {
  const int order = format == "PX4" ? exported_kind(fits).px4_order : kCubic;
  // Which fit serves which axis.
  std::array<const fit::SavedFit*, 3> chosen{};
  if (o.axes.empty()) {
    if (fits.size() > 3)
      throw InputError(fmt::format("{} holds {} channels; choose three with --axes X,Y,Z", o.fit_file, fits.size()));
    for (std::size_t i = 0; i < fits.size(); ++i) chosen[i] = &fits[i];
  } else {
    const std::vector<std::string> names = split_commas(o.axes);
    if (names.size() != 3)
      throw InputError(fmt::format("--axes {}: expected three entries, for X, Y and Z (a channel of the fit, or - "
                                   "for an axis without compensation)",
                                   o.axes));
    for (std::size_t i = 0; i < 3; ++i) {
      if (names[i] == "-") continue;
      std::string known;
      for (const fit::SavedFit& f : fits) {
        if (channel_name(f) == names[i]) chosen[i] = &f;
        known += (known.empty() ? "" : ", ") + channel_name(f);
      }
      if (!chosen[i])
        throw InputError(fmt::format("--axes: '{}' is not a channel of {} (its channels: {})", names[i], o.fit_file,
                                     known));
    }
  }
  std::array<AxisModel, 3> axes;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!chosen[i]) continue;
    const fit::SavedFit& f = *chosen[i];
    if (!f.temp_range_c)
      throw InputError(fmt::format("{}: no data.temp_range_c, the temperature range the model was fitted on (the "
                                   "file was written by an earlier gyrotherm); fit again to export it",
                                   o.fit_file));
    axes[i].present = true;
    axes[i].fit = &f;
    axes[i].channel = channel_name(f);
    axes[i].model = polynomial_of(f, o.drop_unsupported, format, order);
    axes[i].temp_min_c = f.temp_range_c->first;
    axes[i].temp_max_c = f.temp_range_c->second;
    DroppedCost cost{f.instability_after_dph, f.instability_after_dph};
    if (!axes[i].model.dropped.empty()) out->lines.push_back(dropped_report(f, axes[i].model, order, o, &cost));
    warn_if_little_compensation(f, cost.without_dph, out);
  }
  if (std::none_of(axes.begin(), axes.end(), [](const AxisModel& a) { return a.present; }))
    throw InputError("--axes: every axis is '-': nothing to export");
  return axes;
}

FirmwareFile firmware_file(const ExportRequest& r, const std::vector<fit::SavedFit>& fits, const std::string& format) {
  FirmwareFile f;
  f.kind = &exported_kind(fits);
  f.axes = firmware_axes(r, fits, format, &f.out);
  if (single_channel(*f.kind) && (f.axes[1].present || f.axes[2].present || !f.axes[0].present))
    throw InputError(fmt::format("{}: a {}'s thermal compensation holds one channel; give a fit of one (or --axes "
                                 "NAME,-,-)",
                                 r.fit_file, f.kind->noun));
  const auto first = std::find_if(f.axes.begin(), f.axes.end(), [](const AxisModel& a) { return a.present; });
  f.header = export_header(r, *first->fit);
  f.range = export_range(f.axes);
  return f;
}

std::string firmware_wrote(const ExportRequest& r, const FirmwareFile& f, const std::string& format) {
  std::string used;
  for (std::size_t i = 0; i < 3; ++i)
    used += fmt::format("{}{}: {}", i ? ", " : "", "XYZ"[i], f.axes[i].present ? f.axes[i].channel : "-");
  if (single_channel(*f.kind)) used = f.axes[0].channel;  // one channel, no axes
  return fmt::format("wrote {}: {} {} thermal compensation ({}); valid {:.2f} to {:.2f} °C", r.output, format,
                     f.kind->noun, used, f.range.tmin_c, f.range.tmax_c);
}

}  // namespace gyrotherm::studies
