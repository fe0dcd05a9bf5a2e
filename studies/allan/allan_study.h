#pragma once
// `gyrotherm allan`: the Allan deviation of a gyro's output, with intervals
// and noise coefficients, before and after a saved fit's compensation.
//
// With a fit the compensated output is the one a real-time compensator gives:
// the fit's model with backward differences and only windows already complete
// (fit/compensation.h, as `compensate --causal`), subtracted sample by sample.
// Compensation takes out what temperature explains, so the bias instability
// and the rate random walk, where thermal drift shows, should fall; the
// angle random walk, white noise faster than any window, should not.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fit/data/measurement.h"
#include "fit/data/plausibility.h"
#include "fit/data/table.h"
#include "fit/fit_file.h"
#include "studies/allan/allan_curve.h"
#include "studies/allan/noise_coefficients.h"
#include "studies/allan/series_noise.h"

namespace gyrotherm::studies {

struct AllanSeries {
  AllanCurve curve;
  NoiseCoefficients coefficients;
  std::optional<fit::NoiseModel> noise;  // the series' noise model (series_noise.h), if identified
  BiasSupport bias_support = BiasSupport::no_flat_part;  // what makes its bias instability a value or a bound
};

// The Allan curve and coefficients of one series, its noise model identified
// first and used for the noise type at long τ.
// `sensor`: whose series it is (null: a gyro), for the noise model's names.
AllanSeries allan_series(std::span<const double> time_s, std::span<const double> rate_dph,
                         AllanOptions options, std::string name, const fit::SensorKind* sensor = nullptr);

// A record whose temperature moves this much or more carries the gyro's
// thermal drift in its raw rate (°C).
inline constexpr double kThermalDriftSpanC = 2.0;

struct AllanStudy {
  fit::Units units;                   // the log's columns were read in these
  std::vector<fit::UnitCaution> cautions;  // numbers that look like another unit
  std::string data_file, fit_file, channel;
  std::vector<AllanSeries> series;  // "raw", then "compensated" with a fit
  std::size_t outliers = 0;         // samples the fit's glitch rule flagged (kept in both series)
  double temp_span_c = 0.0;         // the record's temperature, highest less lowest sample
  // Whether the raw series' noise model also reads the bias's thermal drift
  // as slow noise: the temperature moved by kThermalDriftSpanC or more.
  bool raw_holds_thermal_drift() const;
  std::string plot;                 // the figure written for it (run_allan with a plot), or ""
  // Raw over compensated bias instability, when both are shown.
  std::optional<double> bias_instability_ratio() const;
};

// `pipeline`: the columns and units the measurement was read with (and, with a
// fit, the fit's own pipeline is used for the compensation).
AllanStudy allan_study(const fit::Measurement& m, const fit::SavedFit* fit, const AllanOptions& options);

// --json: data, fit, channel, confidence, and per series name, tau0_s,
// samples, runs, gaps, taus_s, adev_dph, lo_dph, hi_dph, edf, noise_type,
// noise_type_from ("acf", "model" or "slope"), terms, gap_terms, coefficients
// (arw_dpsh, bias_instability_dph, rrw_dph_per_sqrt_h, quantization_arcsec,
// each {shown, method, value, lo, hi, tau_range_s, tau_read_s, upper_bound,
// note}), bias_instability_support (series_noise.h),
// coefficient_fit_chi2_per_dof and noise_model (fit's noise_model object);
// bias_instability_ratio.
nlohmann::ordered_json allan_json(const AllanStudy& study);

// The report for people: a table per series side by side, the coefficients.
std::string allan_text(const AllanStudy& study);

// `gyrotherm allan` on a log: every gyro channel (pipeline.columns.gyro, a
// comma list) raw, or with a fit every channel it holds, each read with the
// fit's own columns and units, raw and compensated; figures if asked (one per
// channel, STEM_CHANNEL.png beside `plot` when there are several, the channel
// made safe for a file name by fit::channel_file_names).
struct AllanRequest {
  std::string data;
  std::string fit_file;           // "" for none
  std::vector<fit::SavedFit> fits;  // a fit given in memory (the Python package's) in place of fit_file's
  AllanOptions options;
  fit::PipelineOptions pipeline;  // without a fit: the columns and units to read
  // With a fit: the column and unit options given, over the fit's
  // (ColumnMap::unset() fields keep the fit's), as compensate takes them.
  fit::ColumnMap fit_columns = fit::ColumnMap::unset();
  std::string plot;               // a PNG, or ""
};
std::vector<AllanStudy> run_allan(const AllanRequest& request);
// The same on a table of arrays held by the caller (fit/data/table.h), read
// into memory (fit::read_table; with a fit, by its columns, units and --rate,
// not its CSV's text form: fit::for_table); request.data is ignored (the
// studies' data names the table).
std::vector<AllanStudy> run_allan(const AllanRequest& request, const fit::Table& table);
// allan --json: one object, or {"channels": [...]}.
nlohmann::ordered_json allan_json(const std::vector<AllanStudy>& studies);
// The text of every study, and the figures written.
std::string allan_text(const std::vector<AllanStudy>& studies);

// Log-log Allan deviation with the interval bands, the slope lines of the
// coefficients read and their values, every series on one figure.
void write_allan_plot(const std::filesystem::path& png, const AllanStudy& study);

}  // namespace gyrotherm::studies
