// --format ardupilot: ArduPilot's IMU temperature calibration parameters
// (INS_TCAL*), a Mission Planner / MAVProxy .param file
// (studies/export/firmware.h).
#include <fmt/format.h>

#include "studies/export/firmware.h"

namespace gyrotherm::studies {

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

ExporterInfo ardupilot_exporter() {
  return {"ardupilot", "ArduPilot (.param): the INS_TCAL* IMU temperature calibration, a cubic in T",
          [](const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
            FirmwareFile f = firmware_file(r, fits, "ArduPilot");
            f.out.text = ardupilot_parameters(f.axes, r.instance < 0 ? 1 : r.instance, f.header);
            f.out.lines.push_back(firmware_wrote(r, f, "ArduPilot"));
            return f.out;
          }};
}

}  // namespace gyrotherm::studies
