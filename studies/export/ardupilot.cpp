// --format ardupilot: ArduPilot's IMU temperature calibration parameters
// (INS_TCAL*), a Mission Planner / MAVProxy .param file
// (studies/export/firmware.h).
#include <fmt/format.h>

#include "sim/util/input_error.h"
#include "studies/export/firmware.h"
#include "studies/export/firmware_outcome.h"

namespace gyrotherm::studies {

std::optional<std::string> ardupilot_span_caution(const ExportRange& r) {
  if (r.tmax_c - r.tmin_c >= kArduPilotSpanMinimumC) return std::nullopt;
  return fmt::format("the calibration covers {:.1f} °C ({:.1f}..{:.1f} °C), under the {:g} °C ArduPilot requires of "
                     "a temperature calibration: its polynomial says little of the curve beyond these degrees",
                     r.tmax_c - r.tmin_c, r.tmin_c, r.tmax_c, kArduPilotSpanMinimumC);
}

std::string ardupilot_parameters(const std::array<AxisModel, 3>& axes, const std::string& prefix,
                                 const ExportHeader& header) {
  const ExportRange r = export_range(axes);
  std::string out = provenance(header, "#");
  out += R"(#   ArduPilot IMU temperature calibration (AP_InertialSensor::TCal::correct_sensor):
#   p(x) = (GYR1 + (GYR2 + GYR3 x) x) x 1e-6 (rad/s), x = clamp(T, TMIN, TMAX) - 35;
#   corrected = raw - p(x) + p(clamp(T_cal) - 35). The bias at the boot calibration temperature T_cal is
#   taken out by the gyro offsets (INS_GYROFFS_*), so the model's constant is not a parameter here.
#   Loading: the other INS_TCAL parameters appear once ENABLE is 1 and the board rebooted: load this file,
#   reboot, load it again. Boot (INS_GYR_CAL) within TMIN..TMAX: outside, the boot offsets leave a
#   constant error all flight. MAVProxy's param load skips a value within 1e-6 of the vehicle's: use
#   Mission Planner, or param set each. Axes are the IMU's sensor frame, before AHRS_ORIENTATION.
)";
  for (std::size_t i = 0; i < 3; ++i) out += axis_comment(axes[i], std::string(1, "XYZ"[i]), "ArduPilot");
  if (const auto caution = ardupilot_span_caution(r)) out += fmt::format("# CAUTION: {}\n", *caution);
  out += fmt::format("{}ENABLE,1\n", prefix);
  out += fmt::format("{}TMIN,{}\n", prefix, as_float(r.tmin_c));
  out += fmt::format("{}TMAX,{}\n", prefix, as_float(r.tmax_c));
  const std::array<std::array<float, 3>, 3> g = {ardupilot_coefficients(axes[0]), ardupilot_coefficients(axes[1]),
                                                  ardupilot_coefficients(axes[2])};
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < 3; ++i) out += fmt::format("{}GYR{}_{},{}\n", prefix, k + 1, "XYZ"[i], as_float(g[i][k]));
  return out;
}

ExporterInfo ardupilot_exporter() {
  return {"ardupilot", "ArduPilot (.param): the INS_TCAL* IMU temperature calibration, a cubic in T",
          [](const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
            const std::string prefix = ardupilot_prefix(r.instance.value_or(1));
            if (r.device_id != 0) throw InputError("--device-id is PX4's (TC_G{n}_ID); ArduPilot has none");
            FirmwareFile f = firmware_file(r, fits, "ArduPilot");
            f.out.text = ardupilot_parameters(f.axes, prefix, f.header);
            f.out.lines.push_back(firmware_wrote(r, f, "ArduPilot"));
            if (const auto caution = ardupilot_span_caution(f.range)) f.out.warnings.push_back("caution: " + *caution);
            add_outcome(firmware_outcome(Firmware::ardupilot, f, r.data, r.boot_temp_c, r.data_table), &f.out);
            return f.out;
          }};
}

}  // namespace gyrotherm::studies
