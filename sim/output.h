#pragma once
// The simulator's files (docs/contracts.md, "Simulator output"):
//
//   OUT.csv         time_s, chamber_c, case_c, temp_c, temp2_c, gyro_dph, bias_true_dph
//                   (a few '#' comment lines first; no time stamps, so the same
//                   seed gives the same bytes)
//   OUT.truth.json  seed; scenario, rig and gyro files with their SHA-256; the
//                   true coefficients by term name ("1" is the intercept); noise
//                   parameters; hidden effects; solver statistics; energy balance.
//
// Both are written atomically (sim/util/atomic_file.h): first both temporaries, then
// both renames, so a failure leaves neither a half-written file nor a CSV
// without its truth.

#include <filesystem>
#include <string>

#include "sim/simulator.h"

namespace gyrotherm::sim {

// run.csv → run.truth.json (the extension is replaced; none → appended).
std::filesystem::path truth_path_for(const std::filesystem::path& csv);

std::string simulation_csv(const Simulator& simulator, const SimulationResult& result);
// With `record` (the file's name and the SHA-256 of its bytes), the truth
// names the record it belongs to: a fit meets it only on that record.
struct RecordIdentity {
  std::string file, sha256;
};
std::string truth_json(const Simulator& simulator, const SimulationResult& result, const RecordIdentity& record = {});

void write_simulation(const std::filesystem::path& csv, const Simulator& simulator,
                      const SimulationResult& result);

// `simulate --plot`: temperatures (top) and the gyro output as 100 s averages
// with the true bias (bottom), against time in hours (PNG, gnuplot).
void plot_simulation(const std::filesystem::path& png, const Simulator& simulator,
                     const SimulationResult& result);

}  // namespace gyrotherm::sim
