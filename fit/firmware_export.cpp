#include "fit/firmware_export.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "fit/compensation.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

// A value as the firmware stores it (a 32-bit float), written so that it
// reads back to the same float.
std::string as_float(double v) { return fmt::format("{:.9g}", static_cast<float>(v)); }

std::string provenance(const ExportHeader& h, const char* comment) {
  return fmt::format(
      "{0} gyrotherm export: gyro thermal compensation from {1}\n"
      "{0}   fit file SHA-256 {2}\n"
      "{0}   engine {3}, model B = b0 + {4} (°/h, T in °C), exported {5}\n",
      comment, h.fit_file, h.fit_sha256, h.engine, h.model_text, h.date_utc);
}

}  // namespace

double CubicModel::evaluate(double t) const { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }

CubicModel cubic_of(const SavedFit& fit, bool drop_unsupported, const std::string& format) {
  CubicModel m;
  m.c[0] = fit.coefficients.intercept;
  std::vector<std::string> unsupported;
  for (std::size_t k = 0; k < fit.terms.size(); ++k) {
    const std::string name(fit.terms[k]->name);
    const int power = fit.terms[k]->temperature_power;  // 0: not a power of T
    if (power < 1 || power > kCubic) {
      unsupported.push_back(name);
      continue;
    }
    m.c[static_cast<std::size_t>(power)] += fit.coefficients.b[k];
  }
  if (!unsupported.empty() && !drop_unsupported) {
    std::string names;
    for (const std::string& n : unsupported) names += (names.empty() ? "" : ", ") + n;
    throw InputError(fmt::format(
        "{}: the model has {} ({}), which {} cannot express: its gyro thermal compensation is a cubic in "
        "temperature. Use --format c for the whole model, fit a polynomial (--model 'T + T^2 + T^3'), or pass "
        "--drop-unsupported to leave {} out (export then prints how much the instability rises)",
        fit.file.string(), unsupported.size() == 1 ? "a term" : "terms", names, format,
        unsupported.size() == 1 ? "it" : "them"));
  }
  m.dropped = unsupported;
  return m;
}

DroppedCost dropped_cost(const SavedFit& fit, const CubicModel& cubic, const Measurement& data) {
  const Compensation c = compensate(data, fit, reading_columns_of(fit.pipeline, fit.terms));
  std::vector<double> residual;
  for (std::size_t p = 0; p < c.data.series.size(); ++p)
    residual.push_back(c.data.series.gyro_dph[p] - cubic.evaluate(c.data.series.temp_c[p]));
  double mean = 0.0, ss = 0.0;
  for (const double x : residual) mean += x;
  mean /= static_cast<double>(residual.size());
  for (const double x : residual) ss += (x - mean) * (x - mean);
  return {c.after_dph, std::sqrt(ss / static_cast<double>(residual.size() - 1))};
}

std::array<double, 4> reexpand(const CubicModel& m, double r) {
  const auto& c = m.c;
  return {m.evaluate(r), c[1] + r * (2.0 * c[2] + 3.0 * c[3] * r), c[2] + 3.0 * c[3] * r, c[3]};
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

std::string px4_parameters(const std::array<AxisModel, 3>& axes, int instance, long device_id,
                           const ExportHeader& header) {
  const ExportRange r = export_range(axes);
  const float tref = static_cast<float>(r.tref_c);
  std::string out = provenance(header, "#");
  out += fmt::format(
      "#   PX4 gyro thermal compensation (TemperatureCompensation::calc_thermal_offsets_3D):\n"
      "#   offset = X0 + X1 d + X2 d^2 + X3 d^3 (rad/s), d = clamp(T, TMIN, TMAX) - TREF; corrected = raw - offset\n"
      "#   TMIN/TMAX: the window temperatures the model was fitted on. TC_G{0}_ID must be your gyro's device id\n"
      "#   (CAL_GYRO{0}_ID){1}.\n"
      "#   X0 carries the whole bias at TREF: if CAL_GYRO{0}_XOFF/YOFF/ZOFF are also applied, zero them, or the\n"
      "#   bias is taken out twice.\n",
      instance, device_id == 0 ? "; it is 0 here: set it, or pass --device-id" : "");
  for (std::size_t i = 0; i < 3; ++i)
    out += fmt::format("#   axis {}: {}{}\n", i, axes[i].present ? axes[i].channel : "not compensated (zeros)",
                       axes[i].present && !axes[i].model.dropped.empty() ? " (dropped: see export's report)" : "");
  out += "#\n# Vehicle-Id\tComponent-Id\tName\tValue\tType\n";
  const auto line = [&](const std::string& name, const std::string& value, int type) {
    out += fmt::format("1\t1\t{}\t{}\t{}\n", name, value, type);
  };
  line("TC_G_ENABLE", "1", 6);
  line(fmt::format("TC_G{}_ID", instance), std::to_string(device_id), 6);
  line(fmt::format("TC_G{}_TMAX", instance), as_float(r.tmax_c), 9);
  line(fmt::format("TC_G{}_TMIN", instance), as_float(r.tmin_c), 9);
  line(fmt::format("TC_G{}_TREF", instance), as_float(tref), 9);
  for (int k = 0; k <= 3; ++k)
    for (std::size_t i = 0; i < 3; ++i) {
      // Re-expanded about the float TREF the firmware will use.
      const double v = axes[i].present ? reexpand(axes[i].model, tref)[static_cast<std::size_t>(k)] * kRadPerSecPerDegPerHour
                                       : 0.0;
      line(fmt::format("TC_G{}_X{}_{}", instance, k, i), as_float(v), 9);
    }
  return out;
}

std::string ardupilot_parameters(const std::array<AxisModel, 3>& axes, int instance, const ExportHeader& header) {
  const ExportRange r = export_range(axes);
  constexpr double kReference = 35.0;  // TEMP_REFERENCE in AP_InertialSensor_tempcal.cpp
  std::string out = provenance(header, "#");
  out += fmt::format(
      "#   ArduPilot IMU temperature calibration (AP_InertialSensor::TCal::correct_sensor):\n"
      "#   p(x) = (GYR1 + (GYR2 + GYR3 x) x) x 1e-6 (rad/s), x = clamp(T, TMIN, TMAX) - 35;\n"
      "#   corrected = raw - p(x) + p(clamp(T_cal) - 35). The bias at the boot calibration temperature T_cal is\n"
      "#   taken out by the gyro offsets (INS_GYROFFS_*), so the model's constant is not a parameter here.\n");
  for (std::size_t i = 0; i < 3; ++i)
    out += fmt::format("#   axis {}: {}\n", "XYZ"[i], axes[i].present ? axes[i].channel : "not compensated (zeros)");
  out += fmt::format("INS_TCAL{}_ENABLE,1\n", instance);
  out += fmt::format("INS_TCAL{}_TMIN,{}\n", instance, as_float(r.tmin_c));
  out += fmt::format("INS_TCAL{}_TMAX,{}\n", instance, as_float(r.tmax_c));
  for (int k = 1; k <= 3; ++k)
    for (std::size_t i = 0; i < 3; ++i) {
      const double v = axes[i].present
                           ? reexpand(axes[i].model, kReference)[static_cast<std::size_t>(k)] * kRadPerSecPerDegPerHour * 1e6
                           : 0.0;
      out += fmt::format("INS_TCAL{}_GYR{}_{},{}\n", instance, k, "XYZ"[i], as_float(v));
    }
  return out;
}

}  // namespace gyrotherm::fit
