#pragma once
// Applying a saved fit to data (`gyrotherm compensate`).
//
// The model is evaluated where it was fitted, on the window averages:
//   c_p = y_p − B(x_p),  B = b0 + Σ b_j x_pj,
// and the instability before and after is the standard deviation of y_p and of
// c_p (the paper's 100 s instability).
//
// For the full-rate output every sample gets the model of its time:
//   central mode (offline): B interpolated linearly between window centres of
//     the same gap-free run (held flat beyond the first and last centre);
//   causal mode (real time): the real-time compensator of
//     fit/causal_compensator.h, sample by sample: a trailing glitch rule, B of
//     the latest window closed before the sample (before any: of the sample
//     itself), with the fit's sample interval, burst mode and glitch floor.
//     Nothing from the future is used: a record cut short gives the same
//     values up to the cut. The instability before/after is still that of the
//     offline windows, and so is the outlier count in the report.
// compensated = gyro − B: the residual bias, centred near zero.

#include <filesystem>
#include <optional>
#include <utility>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "fit/fit_file.h"

namespace gyrotherm::fit {

// Outside the temperature range a fit was made on: hold the temperature terms
// at the range's edge (what PX4 and ArduPilot do with TMIN/TMAX), or
// evaluate the model anyway.
enum class OutsideRange { hold, extrapolate };

struct Compensation {
  PreparedData data;
  // The fit's range, and the windows whose temperature (as the model reads
  // it) lies outside it; what was done there.
  std::optional<std::pair<double, double>> fit_range_c;
  std::size_t windows_outside = 0;
  OutsideRange outside = OutsideRange::hold;
  std::vector<double> window_model_dph;        // B at each window
  std::vector<double> window_compensated_dph;  // y − B at each window
  double before_dph = 0.0;
  double after_dph = 0.0;
  // Full rate, one per raw sample.
  std::vector<double> time_s, temp_c, gyro_dph, model_dph;
  std::vector<unsigned char> outlier;  // 1 = flagged as a counting glitch
  double ratio() const { return before_dph / after_dph; }
};

// The instability of a series of window averages: its standard deviation
// (two-pass, n − 1), as before_dph and after_dph are computed.
double instability_of(const std::vector<double>& window_averages);

Compensation compensate(const Measurement& measurement, const SavedFit& fit,
                        const PipelineOptions& pipeline, OutsideRange outside = OutsideRange::hold);

// A log too large to hold, one channel (fit/data/streaming.h): the CSV is
// read once, the windows prepared in that pass while the parsed rows go to a
// temporary binary file beside `output` (32 bytes a row; removed on every
// exit); then the full-rate rows of write_compensated_csv are written from it
// as they are computed. Memory stays bounded (the full-rate vectors of the
// result stay empty); the values are compensate()'s on the same windows.
// Without an output, nothing is spilled.
Compensation compensate_streaming(const std::filesystem::path& csv, const SavedFit& fit,
                                  const PipelineOptions& pipeline, const std::filesystem::path& output,
                                  OutsideRange outside = OutsideRange::hold);

// time_s, temp_c, gyro_dph, model_dph, compensated_dph, outlier (atomically).
void write_compensated_csv(const std::filesystem::path& file, const Compensation& c);
// Several channels of the same record: time_s, temp_c, then per channel NAME,
// NAME_model_dph, NAME_compensated_dph, NAME_outlier (atomically).
void write_compensated_csv(const std::filesystem::path& file,
                           const std::vector<std::pair<std::string, Compensation>>& channels);

// The `compensate --json` object: data, fit, model, engine, derivative,
// instability before and after, ratio, windows, outliers removed, output.
nlohmann::ordered_json compensation_json(const Compensation& c, const SavedFit& fit,
                                         const PipelineOptions& pipeline, const std::string& data_file,
                                         const std::string& fit_file, const std::string& output);

}  // namespace gyrotherm::fit
