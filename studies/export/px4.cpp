// --format px4: PX4's gyro thermal compensation parameters (TC_G*), a
// QGroundControl .params file (studies/export/firmware.h).
#include <fmt/format.h>

#include "sim/util/input_error.h"
#include "studies/export/firmware.h"
#include "studies/export/firmware_outcome.h"

namespace gyrotherm::studies {

std::string px4_parameters(const std::array<AxisModel, 3>& axes, int instance, long long device_id,
                           const ExportHeader& header) {
  const ExportRange r = export_range(axes);
  const float tref = static_cast<float>(r.tref_c);
  std::string out = provenance(header, "#");
  out += fmt::format(
      "#   PX4 gyro thermal compensation (TemperatureCompensation::calc_thermal_offsets_3D):\n"
      "#   offset = X0 + X1 d + X2 d^2 + X3 d^3 (rad/s), d = clamp(T, TMIN, TMAX) - TREF; corrected = raw - offset\n"
      "#   TMIN/TMAX: the window temperatures the model was fitted on. TC_G{0}_ID must be your gyro's device id\n"
      "#   (CAL_GYRO{0}_ID){1}.\n"
      "#   Loading: PX4 lists the TC_G* parameters only once TC_G_ENABLE is 1 and the board rebooted: load this\n"
      "#   file, reboot, load it again. Then redo PX4's gyro calibration (X0 holds the whole bias at TREF; offsets\n"
      "#   taken before compensation was enabled would take it out twice). MAVProxy's param load skips a value\n"
      "#   within 1e-6 of the vehicle's: tiny X2/X3 never load that way (use QGroundControl, or param set each).\n"
      "#   Axes are the gyro's sensor frame, before the board rotation (SENS_BOARD_ROT).\n",
      instance, device_id == 0 ? "; it is 0 here: set it, or pass --device-id" : "");
  for (std::size_t i = 0; i < 3; ++i) out += axis_comment(axes[i], std::to_string(i), "PX4");
  out += "#\n# Vehicle-Id\tComponent-Id\tName\tValue\tType\n";
  const auto line = [&](const std::string& name, const std::string& value, int type) {
    out += fmt::format("1\t1\t{}\t{}\t{}\n", name, value, type);
  };
  line("TC_G_ENABLE", "1", 6);
  line(fmt::format("TC_G{}_ID", instance), std::to_string(device_id), 6);
  line(fmt::format("TC_G{}_TMAX", instance), as_float(r.tmax_c), 9);
  line(fmt::format("TC_G{}_TMIN", instance), as_float(r.tmin_c), 9);
  line(fmt::format("TC_G{}_TREF", instance), as_float(tref), 9);
  const std::array<std::array<float, 4>, 3> x = {px4_coefficients(axes[0], tref), px4_coefficients(axes[1], tref),
                                                  px4_coefficients(axes[2], tref)};
  for (std::size_t k = 0; k <= 3; ++k)
    for (std::size_t i = 0; i < 3; ++i) line(fmt::format("TC_G{}_X{}_{}", instance, k, i), as_float(x[i][k]), 9);
  return out;
}

ExporterInfo px4_exporter() {
  return {"px4", "PX4 (QGroundControl .params): the TC_G* gyro thermal compensation, a cubic in T",
          [](const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
            const int instance = px4_instance(r.instance);
            const long long device_id = px4_device_id(r.device_id);
            if (r.boot_temp_c)
              throw InputError("--boot-temp is ArduPilot's (the temperature of its boot gyro calibration); PX4 has none");
            FirmwareFile f = firmware_file(r, fits, "PX4");
            f.out.text = px4_parameters(f.axes, instance, device_id, f.header);
            f.out.lines.push_back(firmware_wrote(r, f, "PX4") +
                                  fmt::format(", TREF {:.2f} °C", static_cast<float>(f.range.tref_c)));
            if (r.device_id == 0)
              f.out.lines.push_back(fmt::format(
                  "set TC_G{0}_ID to your gyro's device id (CAL_GYRO{0}_ID), or pass --device-id", instance));
            add_outcome(firmware_outcome(Firmware::px4, f, r.data, std::nullopt, r.data_table), &f.out);
            return f.out;
          }};
}

}  // namespace gyrotherm::studies
