#pragma once
// A saved fit as an autopilot's thermal compensation parameters
// (`gyrotherm export --format px4|ardupilot`): the parts both formats share
// (studies/export/px4.cpp and ardupilot.cpp write the files). Written for
// the gyro below; the other sensors (fit/data/sensor_kind.h) follow the same
// rules in their own units and parameter names: PX4's TC_A (accelerometer,
// m/s², cubic), TC_B (barometer, Pa, quintic X0..X5, no axis suffix) and
// TC_M (magnetometer, gauss, cubic); ArduPilot's INS_TCAL{n}_ACC{1,2,3}_*
// (accelerometer, m/s² ×10⁶), relative to INS_ACC{n}_CALTEMP as the gyro's
// are to INS_GYR{n}_CALTEMP (ArduPilot has no barometer or compass
// polynomial).
//
// Both firmwares correct a gyro with a cubic in temperature, in rad/s, the
// temperature clamped to the calibrated range:
//
// PX4 (src/modules/temperature_compensation/TemperatureCompensation.cpp,
// calc_thermal_offsets_3D; docs "Thermal Calibration and Compensation"):
//   d = clamp(T, TMIN, TMAX) − TREF,
//   offset = X0 + X1·d + X2·d² + X3·d³,   corrected = raw − offset,
// parameters TC_G{n}_X{k}_{axis} (axis 0, 1, 2), TC_G{n}_TREF, _TMIN, _TMAX,
// TC_G{n}_ID (the gyro's device id) and TC_G_ENABLE, all 32-bit floats
// except the integers ID and ENABLE.
//
// ArduPilot (libraries/AP_InertialSensor/AP_InertialSensor_tempcal.cpp,
// TCal::correct_sensor and polynomial_eval): a fixed reference of 35 °C, no
// constant term, coefficients stored ×10⁶,
//   p(x) = (G1 + (G2 + G3·x)·x)·x · 10⁻⁶,
//   corrected = raw − p(clamp(T) − 35) + p(clamp(T_cal) − 35),
// where T_cal is the temperature of the gyro offset calibration at boot
// (INS_GYR_CALTEMP), whose offsets INS_GYROFFS take out the bias there. So
// the whole correction is B(T) exactly when p(x) = B(35 + x) − B(35): the
// model's constant belongs to the boot calibration, not to these parameters.
// Parameters INS_TCAL{n}_ENABLE, _TMIN, _TMAX, _GYR{1,2,3}_{X,Y,Z}.
//
// The model's polynomial B(T) = c0 + c1·T + c2·T² + c3·T³ (°/h, T in °C) is
// re-expanded about the reference exactly (Taylor: a_k = B⁽ᵏ⁾(T_ref)/k!),
// not refitted, and converted to rad/s (× π/(180·3600)). Stored as 32-bit
// floats the coefficients keep 24 bits (a relative 6·10⁻⁸ each): the
// correction inside the range is the model's to about 10⁻⁷ of the bias.
//
// TMIN/TMAX are the range of the window temperatures the model was fitted
// on (the fit file's data.temp_range_c); outside it the firmwares hold the
// correction at the edge. A model with any term other than a power of T up
// to the third (by the effect registry's temperature_power: dT, grad, T^4, a
// column, a step, … cannot be expressed) is refused, naming the terms, unless
// they are dropped (drop_unsupported), which keeps the other coefficients as
// fitted (not refitted).

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fit/data/table.h"
#include "fit/fit_file.h"
#include "studies/export/exporter.h"

namespace gyrotherm::studies {

// The highest power of T both firmwares store of a gyro (and of an
// accelerometer and a magnetometer); PX4's barometer's.
inline constexpr int kCubic = 3;
inline constexpr int kQuintic = 5;

// B(T) = Σ c[k]·T^k in the sensor's base unit (°/h for a gyro), T in °C;
// c[k] = 0 above the firmware's order.
struct PolynomialModel {
  std::array<double, kQuintic + 1> c{};
  std::vector<std::string> dropped;  // terms left out (drop_unsupported)
  double evaluate(double temp_c) const;
};

// The fit's polynomial in T up to `order`; throws InputError naming the
// terms a firmware cannot express (and suggesting --format c or
// --drop-unsupported) unless drop_unsupported.
PolynomialModel polynomial_of(const fit::SavedFit& fit, bool drop_unsupported, const std::string& format,
                              int order = kCubic);

// a[k] with B(t_ref + d) = Σ a[k]·d^k, exactly.
std::array<double, kQuintic + 1> reexpand(const PolynomialModel& model, double t_ref_c);

// The firmware's unit per the sensor's base unit: rad/s per °/h for a gyro;
// 1 for the others, whose base units (m/s², Pa, gauss) are the firmwares'.
double firmware_per_base(const fit::SensorKind& kind);
// The sensor kind of the fits exported (one for all of them; InputError
// when they differ).
const fit::SensorKind& exported_kind(const std::vector<fit::SavedFit>& fits);

// ArduPilot's fixed reference temperature (TEMP_REFERENCE in AP_InertialSensor_tempcal.cpp).
inline constexpr double kArduPilotReferenceC = 35.0;

inline constexpr double kRadPerSecPerDegPerHour = 3.14159265358979323846 / (180.0 * 3600.0);

// One autopilot axis: a model and its fitted range, or none (not compensated).
struct AxisModel {
  bool present = false;
  const fit::SavedFit* fit = nullptr;  // the fit it came from
  std::string channel;
  PolynomialModel model;
  double temp_min_c = 0.0, temp_max_c = 0.0;
};

struct FirmwareFile;
// The QGroundControl parameter file (vehicle 1, component 1; tab-separated
// "vehicle component name value type", type 9 a float, 6 an integer).
std::string px4_parameters(const FirmwareFile& file, int instance, long long device_id);

// A Mission Planner / MAVProxy parameter file ("NAME,VALUE" lines).
std::string ardupilot_parameters(const FirmwareFile& file, const std::string& prefix);

// What dropping terms costs on the data the fit was made on: the instability
// of the window means with the whole model and with the cubic alone.
struct DroppedCost {
  double with_dph = 0.0, without_dph = 0.0;
};
DroppedCost dropped_cost(const fit::SavedFit& fit, const PolynomialModel& cubic, const fit::Measurement& data);

// The TMIN/TMAX/TREF the exports use: the intersection of the axes' ranges.
struct ExportRange {
  double tmin_c = 0.0, tmax_c = 0.0, tref_c = 0.0;
};
ExportRange export_range(const std::array<AxisModel, 3>& axes);

// The axes of a firmware export from the request: the fit's channels in
// order, or --axes X,Y,Z ('-' for none), each as its cubic; terms dropped
// (--drop-unsupported) are reported in out->lines with their cost, and a
// model that compensates little (with its terms dropped, or as fitted) in
// out->warnings. `format` is the firmware's name for messages ("PX4").
std::array<AxisModel, 3> firmware_axes(const ExportRequest& request, const std::vector<fit::SavedFit>& fits,
                                       const std::string& format, ExportOutput* out);

// ArduPilot's own temperature calibration refuses a span under this (its
// AP_InertialSensor_tempcal; check's calibration_span_minimum the same).
inline constexpr double kArduPilotSpanMinimumC = 10.0;
// "the calibration covers 8.2 °C (15.7..23.8 °C), under the 10 °C ArduPilot
// requires …" for a range under it; nothing for one that is not.
std::optional<std::string> ardupilot_span_caution(const ExportRange& r);

// What both firmware formats write: the sensor kind, the axes, the file's
// header (from the first axis's fit), the range, and export's lines so far
// (dropped terms).
struct FirmwareFile {
  const fit::SensorKind* kind = nullptr;
  std::array<AxisModel, 3> axes;
  ExportHeader header;
  ExportRange range;
  ExportOutput out;
};
FirmwareFile firmware_file(const ExportRequest& request, const std::vector<fit::SavedFit>& fits,
                           const std::string& format);
// "wrote FILE: PX4 gyro thermal compensation (X: gx, Y: -, Z: gz); valid A to B °C"
// (a barometer: "(pressure)")
std::string firmware_wrote(const ExportRequest& request, const FirmwareFile& file, const std::string& format);

// The coefficients as each firmware stores them (32-bit floats): PX4's
// X0..X3 (X0..X5 of a barometer; the rest 0) in the firmware's unit about
// `tref`; ArduPilot's GYR1..3 or ACC1..3 (×10⁶) about 35 °C. A gyro's X0 is
// its whole bias at TREF (PX4's gyro calibration then finds nothing left);
// another sensor's is 0, as PX4's own calibrations set it: what it reads at
// TREF holds gravity, the atmosphere or the Earth's field besides any bias,
// which its offset calibration (CAL_ACCn_XOFF.., CAL_BAROn_OFF, CAL_MAGn_XOFF..)
// takes out; the parameters then correct the change from TREF.
std::array<float, kQuintic + 1> px4_coefficients(const AxisModel& axis, float tref, const fit::SensorKind& kind);
std::array<float, 3> ardupilot_coefficients(const AxisModel& axis, const fit::SensorKind& kind);
// Whether the sensor has one channel (a barometer), not three axes.
bool single_channel(const fit::SensorKind& kind);

// The parameter names' stem of ArduPilot's IMU `instance` (1..5): INS_TCAL1_
// .. INS_TCAL3_, INS4_TCAL_, INS5_TCAL_; throws InputError for another.
std::string ardupilot_prefix(int instance);
// PX4's TC_G{n} instance (0..3) and TC_G{n}_ID (a 32-bit device id, written
// as the int32 parameter holds it); throw InputError naming the valid ones.
int px4_instance(const std::optional<int>& instance);
long long px4_device_id(long long device_id);

// The data a fit was made on, to apply an exported model to: a file, or a
// table of arrays (ExportRequest::data_table, the Python package's data=).
struct FittedData {
  std::string name;                   // the file, or the table's name; empty when not here
  const fit::Table* table = nullptr;
  bool here() const { return !name.empty(); }
  // Read with a fit's columns (a table without their CSV text form).
  fit::Measurement read(const fit::ColumnMap& columns) const;
};
// The data `fit` was made on: `table` if given, else `option` (--data) if
// given, else the fit's own data file (as given to fit, or beside the fit
// file); not here() when none of these is.
FittedData fitted_data(const fit::SavedFit& fit, const std::string& option, const fit::Table* table = nullptr);

// A value as the firmware stores it (a 32-bit float), written so that it
// reads back to the same float.
std::string as_float(double v);
// The file's opening comment lines, each after `comment`.
std::string provenance(const ExportHeader& header, const char* comment);
// A firmware file's line for one of its axes: "#   axis NAME: CHANNEL", with
// the terms left out (--drop-unsupported) that `firmware` cannot express, so
// that the file says its model is not the fit's.
std::string axis_comment(const AxisModel& axis, std::string_view name, std::string_view firmware);
// Its line naming the log the fit was made on, where the fit records it:
// "#   fitted on FILE SHA-256 HEX" (check reads it back: read_parameter_file).
inline constexpr std::string_view kFittedOn = "fitted on ";
inline constexpr std::string_view kFittedSha = " SHA-256 ";  // between FILE and HEX

}  // namespace gyrotherm::studies
