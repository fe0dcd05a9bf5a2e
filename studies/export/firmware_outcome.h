#pragma once
// What a firmware export achieves, predicted on the record the model was
// fitted on, with the firmware's own rule for applying the parameters (the
// formula alone is the model's to 1e-7: studies/export/firmware.h). Three
// numbers per axis, each the instability (std of the window averages, as
// `fit` reports it) of the gyro less what is subtracted:
//
//   model     the fit's model on the windows (the fit file's instability);
//   exported  the exported cubic as stored (32-bit floats), the temperature
//             clamped to [TMIN, TMAX], subtracted from every sample;
//   firmware  as the firmware applies it:
//     PX4 (src/modules/temperature_compensation: TemperatureCompensationModule
//         runs once a second; TemperatureCompensation::update_offsets_gyro
//         re-publishes the offsets only when the temperature has moved more
//         than 1 °C since the last publication): the offsets of the
//         temperature at the last publication, held until the next;
//     ArduPilot (AP_InertialSensor_tempcal.cpp, TCal::correct_sensor, every
//         sample): raw − p(clamp(T) − 35) + p(clamp(T_boot) − 35), the gyro
//         offsets taken at boot at T_boot removing the bias there; a boot
//         outside [TMIN, TMAX] leaves a constant error B(T_boot) −
//         B(clamp(T_boot)) all flight (by the model, extrapolated), which a
//         standard deviation does not show, so it is reported beside it.
//
// Where the firmware's rule leaves more than 20 % above the model, a note
// says so and what would help.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fit/data/measurement.h"
#include "fit/data/plausibility.h"
#include "studies/export/firmware.h"

namespace gyrotherm::studies {

// What PX4 subtracts from each sample, in the sensor's base unit (°/h for a
// gyro): offsets (X0..X3, or a barometer's X0..X5, in the firmware's unit as
// stored; `per_base`: firmware_per_base) recomputed once a second from the
// latest sample's temperature and applied from the first update on, then only
// when the temperature has moved more than 1 °C since the last applied one.
std::vector<double> px4_applied_dph(const std::vector<double>& time_s, const std::vector<double>& temp_c,
                                    std::span<const float> x, float tref, float tmin, float tmax,
                                    double per_base = kRadPerSecPerDegPerHour);

// What ArduPilot subtracts from each sample (in the base unit), GYR1..3 or
// ACC1..3 as stored (×1e6), after offsets taken at boot_c (the gyro's boot
// calibration, the accelerometer's calibration): p(clamp(T) − 35) −
// p(clamp(boot) − 35) + B_boot, where B_boot (the bias there) is what the
// offsets remove.
std::vector<double> ardupilot_applied_dph(const std::vector<double>& temp_c, const std::array<float, 3>& g,
                                          float tmin, float tmax, float boot_c, double bias_at_boot_dph,
                                          double per_base = kRadPerSecPerDegPerHour);

enum class Firmware { px4, ardupilot };

// Where the firmware's rule costs more than 20 % above the model, why (the
// notes say what would help).
enum class FirmwareCost {
  none,            // within 20 %
  exported_cubic,  // the exported cubic already leaves it (terms dropped, or samples held at the range's edge)
  px4_step,        // PX4's 1 °C step
  held_edge,       // ArduPilot: samples outside the fitted range held at its edge
};

struct AxisOutcome {
  char axis = 'X';
  std::string channel;
  double before_dph = 0, model_dph = 0, exported_dph = 0, firmware_dph = 0;
  double boot_error_dph = 0;  // ArduPilot: the constant a boot outside the range leaves
  FirmwareCost cost = FirmwareCost::none;
  // What makes an exported cubic cost: the fit's terms it left out, and the
  // share of the record's samples outside the fitted range (held at its edge).
  std::vector<std::string> dropped;
  double outside_share = 0;
  bool edge_costs = false;  // holding those samples at the edge costs more than 5 % against not holding them
};

// A record's unit caution (fit/data/plausibility.h), worded by fit::caution_text.
struct RecordCaution {
  std::string data;  // the record's name
  fit::UnitCaution caution;
};

// The outcome as data; json(), lines() and warnings() word it.
struct FirmwareOutcome {
  Firmware firmware = Firmware::px4;
  const fit::SensorKind* kind = &fit::sensor_kinds().front();  // every number in its base unit (kind->unit)
  std::string data;                // the record it was computed on; empty: not here
  // Not here: the fit file and the data it names (the notes say to give it with --data).
  std::string fit_file, missing_data;
  std::vector<AxisOutcome> axes;   // the axes exported
  // The records' unit cautions, each once.
  std::vector<RecordCaution> cautions;
  // ArduPilot: a --boot-temp outside the fitted range [tmin_c, tmax_c].
  std::optional<double> boot_outside_c;
  double tmin_c = 0.0, tmax_c = 0.0;
  nlohmann::ordered_json json() const;
  std::vector<std::string> lines() const;     // for the terminal
  std::vector<std::string> notes() const;     // where the rule costs more than 20 %, and what would help
  std::vector<std::string> warnings() const;  // for stderr
  // "cubic", or "quintic" (PX4's barometer).
  std::string_view polynomial() const {
    return firmware == Firmware::px4 && kind->px4_order == kQuintic ? "quintic" : "cubic";
  }
};

// The outcome of `file` applied by `firmware` on the data each axis's fit was
// made on (`data_table`, else `data_option`, else the fit's own file); without that data, an
// outcome with an empty `data` and a note saying what to give.
// `boot_c`: ArduPilot's boot temperature (default: the record's first).
FirmwareOutcome firmware_outcome(Firmware firmware, const FirmwareFile& file, const std::string& data_option,
                                 std::optional<double> boot_c, const fit::Table* data_table = nullptr);

// Export's lines, warnings and JSON ("firmware_outcome") with the outcome's.
void add_outcome(const FirmwareOutcome& outcome, ExportOutput* out);

}  // namespace gyrotherm::studies
