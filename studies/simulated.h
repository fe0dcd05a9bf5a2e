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
};
// The truth beside a CSV written by `gyrotherm simulate`, if there is one.
std::optional<Truth> load_truth_beside(const std::filesystem::path& csv);
// The truth in a parsed truth JSON (sim/output.h's truth_json); `file` names it in messages.
Truth truth_from_json(const nlohmann::json& truth, const std::filesystem::path& file);
// Relative error (fit − true)/|true| per model term and "1"; terms whose true
// value is 0 (absent from the truth) are left out.
std::map<std::string, double> coefficient_errors(const fit::ModelFit& fit, const Truth& truth);
// Appends truth, truth_parameters and coefficient_error to a fit's JSON.
void add_truth(nlohmann::ordered_json& fit_json, const fit::ModelFit& fit, const Truth& truth);

}  // namespace gyrotherm::studies
