#pragma once
// Where a simulated record meets the fitter (the simulator and the fitter do
// not know each other; studies join them): a simulation as a measurement, and
// the ground truth `gyrotherm simulate` writes beside its CSV (run.csv →
// run.truth.json), read back and set against a fit.

#include <filesystem>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "fit/data/measurement.h"
#include "fit/pipeline.h"
#include "sim/simulator.h"

namespace gyrotherm::studies {

// A simulated record as a measurement (time, temp_c, temp2_c, gyro_dph), as
// if read from its CSV without the rounding; `file` names it in messages.
fit::Measurement measurement_of(sim::SimulationResult record, std::string file);

struct Truth {
  std::filesystem::path file;
  std::map<std::string, double> coefficients;  // term → value, "1" = intercept
  std::map<std::string, double> parameters;    // term → its nonlinear parameter (hidden effects)
  // Found for its channel by name (a truth with channels), so it holds when
  // several channels are fitted; otherwise only for a fit of one.
  bool channel_matched = false;
};
// The truth beside a record written by `gyrotherm simulate` (a CSV or a
// log), if there is one, for its channel `column`: the gyro's for gyro_dph
// (a log's gyro_x), a channel's for its CSV column (accel_x_mps2) or its
// log column (accel_x, pressure), none for any other column. A truth
// without channels (a gyro file without [[channel]]s) is its gyro's, for
// whichever one column is fitted; "" asks for the gyro's. A truth that
// names another record (its "record" file: imu.csv's truth beside imu.ulg,
// the two sharing imu.truth.json) is none.
std::optional<Truth> load_truth_beside(const std::filesystem::path& record, std::string_view column = {});
// The truth in a parsed truth JSON (sim/output.h's truth_json); `file` names it in messages.
Truth truth_from_json(const nlohmann::json& truth, const std::filesystem::path& file);
// The truth of channel `column` in a parsed truth JSON, as load_truth_beside.
std::optional<Truth> channel_truth(const nlohmann::json& truth, const std::filesystem::path& file,
                                   std::string_view column);
// Relative error (fit − true)/|true| per model term and "1"; terms whose true
// value is 0 (absent from the truth) are left out.
std::map<std::string, double> coefficient_errors(const fit::ModelFit& fit, const Truth& truth);
// Appends truth, truth_parameters and coefficient_error to a fit's JSON.
void add_truth(nlohmann::ordered_json& fit_json, const fit::ModelFit& fit, const Truth& truth);

}  // namespace gyrotherm::studies
