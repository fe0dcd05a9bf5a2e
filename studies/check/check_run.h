#pragma once
// `gyrotherm check LOG --params FILE`: a calibration applied to another log
// as the firmware applies it, and judged (docs/contracts.md, "check").
//
//   PX4 (.params): the offsets of TC_G{n} recomputed once a second and
//     re-applied after the temperature has moved more than 1 °C, the
//     temperature clamped to TMIN..TMAX (studies/export/firmware_outcome.h);
//     the set whose TC_G{n}_ID is the log gyro's device id, as PX4 chooses.
//   ArduPilot (.parm): every sample, p(clamp(T) − 35) − p(clamp(T_cal) − 35)
//     plus the gyro offsets taken at boot, T_cal the boot temperature
//     (INS_GYR_CALTEMP): the boot is the log's first `boot_s` seconds (the
//     mean rate there is the offsets; ArduPilot calibrates the gyros at every
//     boot by default).
//   fit file: the model as `compensate` applies it (held at the fitted range).
//
// Per axis: the instability (std of window means) raw and compensated; the
// residual against temperature, the mean compensated rate in temperature
// bins, with its constant part (the offset a boot calibration or the
// estimator removes) told apart from the part that varies with temperature
// (`residual_dph`, the largest |bin mean − offset|, what --max-residual
// judges); the share of samples outside TMIN..TMAX. Findings: the failure
// modes users of both autopilots report (CheckIssue).

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fit/data/measurement.h"
#include "fit/data/plausibility.h"
#include "studies/check/check_parameters.h"
#include "studies/export/exporter.h"

namespace gyrotherm::studies {

struct CheckRequest {
  std::string log;         // the second log: a PX4 ULog, an ArduPilot DataFlash log or a measurement CSV
  std::string parameters;  // --params: PX4 .params, ArduPilot .parm or a fit file
  double avg_s = 100.0;    // --avg: the instability's window (shortened to a tenth of a short log)
  double boot_s = 10.0;    // --boot: ArduPilot's boot gyro calibration, the log's first seconds
  std::optional<double> max_residual;  // --max-residual, in residual_unit
  std::string residual_unit;  // --residual-unit: one of the sensor's units ("": its base unit, dph for a gyro)
  // Columns and units of a CSV log (unset: the defaults; a fit file's own for
  // a fit); `imu` (--imu) the log's gyro instance (default: the one the
  // calibration is for), of a CSV the calibration's instance.
  fit::ColumnMap columns = fit::ColumnMap::unset();
};

// The failure modes, in the order they are reported.
enum class CheckIssue {
  calibration_span_minimum,  // TMAX − TMIN under 10 °C (ArduPilot's minimum)
  calibration_span_advice,   // under 25 °C (ArduPilot's advice)
  log_span_minimum,          // the log spans under 10 °C: it can say little about the temperature dependence
  temperature_quantised,     // the log's temperature in whole degrees (Bosch parts)
  moving,                    // gyro beyond the rest rate, or the accelerometer moving
  already_enabled,           // the log was written with these corrections on: double correction
  device_mismatch,           // the calibration's device id is no gyro of the log: the firmware would not apply it
  outside_range,             // samples outside TMIN..TMAX (held at the edge)
  residual_over_limit,       // --max-residual exceeded
  fitted_log,                // the log is the one the fit was made on (same SHA-256): no second test
  no_residual,               // no temperature bin has enough samples: the residual cannot be shown (`name` the axis)
  made_worse,                // the calibration leaves an axis's instability above the uncompensated (value: after/before)
  little_gain,               // it takes under 20 % off an axis's instability on this log (value: after/before)
  calibration_caution,       // the parameter file carries a caution of its export (`name` its text)
};
// An axis whose instability the calibration leaves above this many times the
// uncompensated is made worse (and fails --max-residual); one left above
// kLittleGain (under 20 % off: export's kLittleCompensation) gains little.
inline constexpr double kMadeWorse = 1.05;
inline constexpr double kLittleGain = kLittleCompensation;
// "calibration_span_minimum", …
std::string_view check_issue_name(CheckIssue issue);
// Whether a finding means this log cannot pass the calibration under
// --max-residual (made_worse, fitted_log, moving, already_enabled,
// device_mismatch); the others are advice.
bool blocks_a_pass(CheckIssue issue);

// A gyro of the log by its device id: a ULog sensor_gyro instance, or the
// DataFlash parameter that records it (instance −1 there).
struct LogDevice {
  long long device_id = 0;
  int instance = -1;
  std::string parameter;  // ArduPilot: INS_GYR{n}_ID; PX4: ""
};

struct CheckFinding {
  CheckIssue issue = CheckIssue::moving;
  double value = 0.0;  // span °C; step °C; moving share; enable value; device id; share outside; residual °/h
  double limit = 0.0;  // the threshold it is judged against (0 where none)
  std::string name;    // the parameter, the axis or the sensor ("gyro", "accelerometer")
  std::vector<LogDevice> devices;  // device_mismatch: the log's gyros it was compared with
};

// Mean compensated rate of the samples in one temperature bin.
struct TemperatureBin {
  double low_c = 0.0, high_c = 0.0;
  std::size_t samples = 0;
  double mean_dph = 0.0;
};

struct AxisCheck {
  std::string axis;  // "X", "Y", "Z", or the fit's channel
  double before_dph = 0.0, after_dph = 0.0;
  double offset_dph = 0.0;    // the mean compensated rate: the constant left
  double residual_dph = NAN;  // the largest |bin mean − offset| (NaN: no bin has enough samples)
  double residual_at_c = NAN; // the centre of that bin
  std::vector<TemperatureBin> bins;
  double outside_share = 0.0;  // samples outside TMIN..TMAX
  // The window means (the instability's windows) of the time and of the rate
  // raw and as the calibration leaves it: for a figure (report).
  std::vector<double> window_time_s, window_raw_dph, window_compensated_dph;
};

struct CheckResult {
  CheckRequest request;
  ParameterFormat format = ParameterFormat::fit;
  const fit::SensorKind* sensor = &fit::sensor_kinds().front();  // whose calibration; the *_dph fields in its unit
  std::string log_format;       // "ULog v1", "DataFlash", "CSV"
  int log_instance = -1;        // the log's gyro checked (-1: a CSV)
  long long log_device_id = 0;  // its device id (0: unknown)
  std::string calibration;      // "TC_G0_", "INS_TCAL1_", or the fit file
  double tmin_c = 0.0, tmax_c = 0.0;
  double boot_c = 0.0;          // ArduPilot: the temperature of the boot calibration
  double log_temp_min_c = 0.0, log_temp_max_c = 0.0, span_s = 0.0;
  std::size_t samples = 0;
  double window_s = 0.0;
  double bin_c = 0.0;
  // A fit file: the samples its glitch rule flags (any channel). check keeps
  // them, as a firmware would; compensate's figure leaves them out.
  std::size_t glitches_flagged = 0;
  std::vector<AxisCheck> axes;
  std::vector<CheckFinding> findings;
  // The log's units checked as fit checks them (a CSV's; a fit file's channels), each worded once.
  std::vector<fit::UnitCaution> cautions;
  std::optional<double> limit_dph;  // --max-residual in °/h (the sensor's base unit)
  // With a limit: whether every axis's residual is within it.
  std::optional<bool> passed;
  int exit_code() const { return passed.has_value() && !*passed ? 1 : 0; }
};

CheckResult run_check(const CheckRequest& request);
nlohmann::ordered_json check_json(const CheckResult& result);
std::string check_text(const CheckResult& result);

}  // namespace gyrotherm::studies
