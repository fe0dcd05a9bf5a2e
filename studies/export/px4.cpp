// --format px4: PX4's thermal compensation parameters of a gyro (TC_G*), an
// accelerometer (TC_A*), a barometer (TC_B*) or a magnetometer (TC_M*), a
// QGroundControl .params file (studies/export/firmware.h).
#include <fmt/format.h>

#include "fit/data/sensor_kind.h"
#include "sim/util/input_error.h"
#include "studies/export/firmware.h"
#include "studies/export/firmware_outcome.h"

namespace gyrotherm::studies {
namespace {

// What the file's comment says of a sensor other than the gyro: the rule,
// and that X0 is 0 (firmware.h: px4_coefficients).
std::string other_sensor_comment(const fit::SensorKind& kind, int instance, long long device_id) {
  const bool one = single_channel(kind);
  std::string powers;
  for (int k = 1; k <= kind.px4_order; ++k) powers += fmt::format(" + X{0} d^{0}", k);
  return fmt::format(
      "#   PX4 {0} thermal compensation (TemperatureCompensation::calc_thermal_offsets_{1}):\n"
      "#   offset = X0{2} ({3}), d = clamp(T, TMIN, TMAX) - TREF; corrected = raw - offset\n"
      "#   TMIN/TMAX: the window temperatures the model was fitted on. {4}{5}_ID must be your {0}'s device id\n"
      "#   ({6}{5}_ID){7}.\n"
      "#   X0 is 0: what the {0} reads at TREF is left to its offset calibration ({6}{5}_{8}), as PX4's own\n"
      "#   thermal calibration leaves it; these parameters correct the change from TREF.\n"
      "#   Loading: PX4 lists the {4}* parameters only once {4}_ENABLE is 1 and the board rebooted: load this\n"
      "#   file, reboot, load it again. MAVProxy's param load skips a value within 1e-6 of the vehicle's: tiny\n"
      "#   coefficients never load that way (use QGroundControl, or param set each).\n",
      kind.noun, one ? "1D" : "3D", powers, kind.ulog.unit == "mps2" ? "m/s^2" : kind.ulog.unit, kind.px4_stem,
      instance, kind.px4_calibration, device_id == 0 ? "; it is 0 here: set it, or pass --device-id" : "",
      one ? "OFF" : "XOFF, _YOFF, _ZOFF");
}

}  // namespace

std::string px4_parameters(const FirmwareFile& f, int instance, long long device_id) {
  const fit::SensorKind& kind = *f.kind;
  const ExportRange& r = f.range;
  const float tref = static_cast<float>(r.tref_c);
  std::string out = provenance(f.header, "#");
  if (kind.is_gyro)
    out += fmt::format(
        "#   PX4 gyro thermal compensation (TemperatureCompensation::calc_thermal_offsets_3D):\n"
        "#   offset = X0 + X1 d + X2 d^2 + X3 d^3 (rad/s), d = clamp(T, TMIN, TMAX) - TREF; corrected = raw - offset\n"
        "#   TMIN/TMAX: the window temperatures the model was fitted on. TC_G{0}_ID must be your gyro's device id\n"
        "#   (CAL_GYRO{0}_ID){1}.\n"
        "#   Loading: PX4 lists the TC_G* parameters only once TC_G_ENABLE is 1 and the board rebooted: load this\n"
        "#   file, reboot, load it again. Then redo PX4's gyro calibration (X0 holds the whole bias at TREF; offsets\n"
        "#   taken before compensation was enabled would take it out twice). MAVProxy's param load skips a value\n"
        "#   within 1e-6 of the vehicle's: tiny X2/X3 never load that way (use QGroundControl, or param set each).\n",
        instance, device_id == 0 ? "; it is 0 here: set it, or pass --device-id" : "");
  else
    out += other_sensor_comment(kind, instance, device_id);
  if (!single_channel(kind)) {
    out += fmt::format("#   Axes are the {}'s sensor frame, before the board rotation (SENS_BOARD_ROT).\n", kind.noun);
    for (std::size_t i = 0; i < 3; ++i) out += axis_comment(f.axes[i], std::to_string(i), "PX4");
  } else {
    out += axis_comment(f.axes[0], "-", "PX4");
  }
  out += "#\n# Vehicle-Id\tComponent-Id\tName\tValue\tType\n";
  const auto line = [&](const std::string& name, const std::string& value, int type) {
    out += fmt::format("1\t1\t{}\t{}\t{}\n", name, value, type);
  };
  const std::string_view stem = kind.px4_stem;
  line(fmt::format("{}_ENABLE", stem), "1", 6);
  line(fmt::format("{}{}_ID", stem, instance), std::to_string(device_id), 6);
  line(fmt::format("{}{}_TMAX", stem, instance), as_float(r.tmax_c), 9);
  line(fmt::format("{}{}_TMIN", stem, instance), as_float(r.tmin_c), 9);
  line(fmt::format("{}{}_TREF", stem, instance), as_float(tref), 9);
  const auto k_max = static_cast<std::size_t>(kind.px4_order);
  if (single_channel(kind)) {
    const std::array<float, kQuintic + 1> x = px4_coefficients(f.axes[0], tref, kind);
    for (std::size_t k = 0; k <= k_max; ++k) line(fmt::format("{}{}_X{}", stem, instance, k), as_float(x[k]), 9);
    return out;
  }
  const std::array<std::array<float, kQuintic + 1>, 3> x = {
      px4_coefficients(f.axes[0], tref, kind), px4_coefficients(f.axes[1], tref, kind),
      px4_coefficients(f.axes[2], tref, kind)};
  for (std::size_t k = 0; k <= k_max; ++k)
    for (std::size_t i = 0; i < 3; ++i) line(fmt::format("{}{}_X{}_{}", stem, instance, k, i), as_float(x[i][k]), 9);
  return out;
}

// For --help.
constexpr const char* kPx4Description =
    "PX4 (QGroundControl .params): the TC_G* gyro thermal compensation, a cubic in T (TC_A* of an accelerometer, "
    "TC_B* of a barometer, a quintic, TC_M* of a magnetometer)";

ExporterInfo px4_exporter() {
  return {"px4", kPx4Description,
          [](const ExportRequest& r, const std::vector<fit::SavedFit>& fits) {
            const int instance = px4_instance(r.instance);
            const long long device_id = px4_device_id(r.device_id);
            if (r.boot_temp_c)
              throw InputError("--boot-temp is ArduPilot's (the temperature of its boot gyro calibration, or of its "
                               "accelerometer calibration); PX4 has none");
            FirmwareFile f = firmware_file(r, fits, "PX4");
            f.out.text = px4_parameters(f, instance, device_id);
            f.out.lines.push_back(firmware_wrote(r, f, "PX4") +
                                  fmt::format(", TREF {:.2f} °C", static_cast<float>(f.range.tref_c)));
            if (r.device_id == 0)
              f.out.lines.push_back(fmt::format("set {}{}_ID to your {}'s device id ({}{}_ID), or pass --device-id",
                                                f.kind->px4_stem, instance, f.kind->noun, f.kind->px4_calibration,
                                                instance));
            add_outcome(firmware_outcome(Firmware::px4, f, r.data, std::nullopt, r.data_table), &f.out);
            return f.out;
          }};
}

}  // namespace gyrotherm::studies
