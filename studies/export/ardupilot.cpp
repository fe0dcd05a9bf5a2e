// --format ardupilot: ArduPilot's IMU temperature calibration parameters
// (INS_TCAL*), a Mission Planner / MAVProxy .param file
// (studies/export/firmware.h).
#include <fmt/format.h>

#include "fit/data/sensor_kind.h"
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

std::string ardupilot_parameters(const FirmwareFile& f, const std::string& prefix) {
  const fit::SensorKind& kind = *f.kind;
  const ExportRange& r = f.range;
  std::string out = provenance(f.header, "#");
  if (kind.is_gyro)
    out += R"(#   ArduPilot IMU temperature calibration (AP_InertialSensor::TCal::correct_sensor):
#   p(x) = (GYR1 + (GYR2 + GYR3 x) x) x 1e-6 (rad/s), x = clamp(T, TMIN, TMAX) - 35;
#   corrected = raw - p(x) + p(clamp(T_cal) - 35). The bias at the boot calibration temperature T_cal is
#   taken out by the gyro offsets (INS_GYROFFS_*), so the model's constant is not a parameter here.
#   Loading: the other INS_TCAL parameters appear once ENABLE is 1 and the board rebooted: load this file,
#   reboot, load it again. Boot (INS_GYR_CAL) within TMIN..TMAX: outside, the boot offsets leave a
#   constant error all flight. MAVProxy's param load skips a value within 1e-6 of the vehicle's: use
#   Mission Planner, or param set each. Axes are the IMU's sensor frame, before AHRS_ORIENTATION.
)";
  else
    out += fmt::format(
        "#   ArduPilot IMU temperature calibration (AP_InertialSensor::TCal::correct_sensor):\n"
        "#   p(x) = ({0}1 + ({0}2 + {0}3 x) x) x 1e-6 (m/s^2), x = clamp(T, TMIN, TMAX) - 35;\n"
        "#   corrected = raw - p(x) + p(clamp(T_cal) - 35), T_cal the temperature of the accelerometer calibration\n"
        "#   (INS_ACC{{n}}_CALTEMP), whose offsets (INS_ACCOFFS_*) take out the bias there, so the model's constant\n"
        "#   is not a parameter here. TMIN and TMAX are the gyro's too (GYR*): loading this file after a gyro's\n"
        "#   sets them to this {1}'s range; export both from fits over the same range.\n"
        "#   Loading: the other INS_TCAL parameters appear once ENABLE is 1 and the board rebooted: load this file,\n"
        "#   reboot, load it again. MAVProxy's param load skips a value within 1e-6 of the vehicle's: use\n"
        "#   Mission Planner, or param set each. Axes are the IMU's sensor frame, before AHRS_ORIENTATION.\n",
        kind.ardupilot_group, kind.noun);
  for (std::size_t i = 0; i < 3; ++i) out += axis_comment(f.axes[i], std::string(1, "XYZ"[i]), "ArduPilot");
  if (const auto caution = ardupilot_span_caution(r)) out += fmt::format("# CAUTION: {}\n", *caution);
  out += fmt::format("{}ENABLE,1\n", prefix);
  out += fmt::format("{}TMIN,{}\n", prefix, as_float(r.tmin_c));
  out += fmt::format("{}TMAX,{}\n", prefix, as_float(r.tmax_c));
  const std::array<std::array<float, 3>, 3> g = {ardupilot_coefficients(f.axes[0], kind),
                                                  ardupilot_coefficients(f.axes[1], kind),
                                                  ardupilot_coefficients(f.axes[2], kind)};
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < 3; ++i)
      out += fmt::format("{}{}{}_{},{}\n", prefix, kind.ardupilot_group, k + 1, "XYZ"[i], as_float(g[i][k]));
  return out;
}

ExporterInfo ardupilot_exporter() {
  return {"ardupilot",
          "ArduPilot (.param): the INS_TCAL* IMU temperature calibration, a cubic in T (GYR* of a gyro, ACC* of an "
          "accelerometer)",
          [](const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
            const std::string prefix = ardupilot_prefix(r.instance.value_or(1));
            if (r.device_id != 0) throw InputError("--device-id is PX4's (TC_G{n}_ID, TC_A{n}_ID, ...); ArduPilot has none");
            if (const fit::SensorKind& kind = exported_kind(fits); kind.ardupilot_group.empty())
              throw InputError(fmt::format("{}: the fit of a {}: ArduPilot has no temperature calibration of a {} "
                                           "(its INS_TCAL parameters are the gyros' and accelerometers'); export "
                                           "it with --format px4 (TC_B, TC_M)",
                                           r.fit_file, kind.noun, kind.noun));
            FirmwareFile f = firmware_file(r, fits, "ArduPilot");
            f.out.text = ardupilot_parameters(f, prefix);
            f.out.lines.push_back(firmware_wrote(r, f, "ArduPilot"));
            if (const auto caution = ardupilot_span_caution(f.range)) f.out.warnings.push_back("caution: " + *caution);
            add_outcome(firmware_outcome(Firmware::ardupilot, f, r.data, r.boot_temp_c, r.data_table), &f.out);
            return f.out;
          }};
}

}  // namespace gyrotherm::studies
