#pragma once
// The calibration `gyrotherm check` applies to a second log (docs/contracts.md,
// "check"): a parameter file as the firmware loads it, or a fit file.
//
//   PX4 .params   QGroundControl's "vehicle component name value type" lines
//                 (tab- or space-separated; what `export --format px4` and
//                 PX4's Tools/process_sensor_caldata.py write), '#' comments;
//   ArduPilot     "NAME,VALUE" (Mission Planner, `export --format ardupilot`)
//   .parm         or "NAME VALUE" (MAVProxy, Tools/scripts/tempcal_IMU.py),
//                 '#' comments, also after a value;
//   fit file      `gyrotherm fit -o` (a JSON object).
//
// The format is told by the text: a JSON object is a fit file; PX4's lines
// have five fields; ArduPilot's two. Which firmware and sensor the
// parameters are for is told by their names (PX4's TC_G*, TC_A*, TC_B*,
// TC_M*; ArduPilot's INS_TCAL*/INS4_TCAL*/INS5_TCAL* _GYR* and _ACC*; the
// stems of fit/data/sensor_kind.h). Bad input — a line of neither form, a
// value that is not a finite number, a name given twice with two values, a
// file with no thermal parameters of the sensor asked for — throws
// InputError naming the file and line.

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fit/data/sensor_kind.h"
#include "fit/fit_file.h"

namespace gyrotherm::studies {

enum class ParameterFormat { px4, ardupilot, fit };
// "px4", "ardupilot", "fit"
std::string_view parameter_format_name(ParameterFormat format);

struct ParameterFile {
  std::string file;
  ParameterFormat format = ParameterFormat::fit;
  std::map<std::string, double, std::less<>> values;  // PX4 / ArduPilot, by name
  std::vector<fit::SavedFit> fits;                     // a fit file's channels
  // PX4 / ArduPilot: the file's "# CAUTION …" comments (export --accept-caution,
  // a narrow span), each with its indented lines joined.
  std::vector<std::string> cautions;
  // The log the fit was made on and its SHA-256, where the file records them:
  // a fit file's data (the first channel that has it), a PX4 / ArduPilot
  // file's provenance ("#   fitted on FILE SHA-256 HEX").
  std::string fitted_file, fitted_sha256;
  // The sensor the calibration is for: a fit file's, or the kind whose
  // parameters the file holds.
  const fit::SensorKind* kind = &fit::sensor_kinds().front();
  std::optional<double> value(std::string_view name) const;
};

// `sensor`: --sensor as given ("" when not): a file of PX4 or ArduPilot
// parameters is read for that kind (not given: the one kind whose
// parameters it holds, the gyro when several); a fit file must be that
// kind's. A file without the kind's parameters, or a fit of another kind,
// is refused naming what it holds.
ParameterFile read_parameter_file(const std::string& file, std::string_view sensor = {});

// One sensor's thermal calibration from a PX4 or ArduPilot parameter file
// (of the file's kind).
struct GyroCalibration {
  ParameterFormat format = ParameterFormat::px4;
  int instance = 0;    // PX4: n of TC_G{n}_; ArduPilot: the IMU instance (INS_TCAL1_ is 0)
  std::string prefix;  // "TC_G0_", "TC_A1_", "INS_TCAL1_", "INS4_TCAL_"
  std::optional<double> enable;  // TC_G_ENABLE / INS_TCAL{n}_ENABLE as the file sets it
  double tmin_c = 0.0, tmax_c = 0.0;
  float tref_c = 0.0f;                   // PX4's TREF; ArduPilot's fixed 35 °C
  std::optional<long long> device_id;    // PX4's TC_G{n}_ID; ArduPilot's INS_GYR{,2,3}_ID when the file has it
  std::array<bool, 3> axes{};            // X, Y, Z given (a barometer: X alone, its pressure)
  // X0.. per axis, in the log's unit (rad/s for a gyro): X0..X3, a barometer's
  // X0..X5 (the file's kind's px4_order).
  std::array<std::array<float, 6>, 3> px4_x{};
  std::array<std::array<float, 3>, 3> ap_g{};   // GYR1..3 or ACC1..3 per axis (×1e6 rad/s, m/s²)
};

// The calibrations of the file's kind it holds, lowest instance first (none
// for a fit file). A calibration missing one of its range or coefficient
// parameters is an InputError naming it.
std::vector<GyroCalibration> gyro_calibrations(const ParameterFile& file);

// ArduPilot's parameter holding the device id of IMU `instance` (0-based):
// INS_GYR_ID, INS_GYR2_ID, INS_GYR3_ID, INS4_GYR_ID, INS5_GYR_ID (the
// accelerometer's INS_ACC_ID, …, with `group` ACC).
std::string ardupilot_gyro_id_name(int instance, std::string_view group = "GYR");

}  // namespace gyrotherm::studies
