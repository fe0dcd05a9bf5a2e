#pragma once
// The fit's JSON: what `fit --json` prints and `fit -o FIT.json` saves, and
// what `compensate --fit FIT.json` reads back. Fields (docs/contracts.md): engine,
// model, coefficients (term → value, the intercept under "1"),
// instability_before_dph, instability_after_dph, ratio, objective,
// evaluations, iterations, seconds, termination, history; with data from
// `simulate`, truth and coefficient_error. Also saved, for compensate:
// parameters of nonlinear terms, the pipeline (window, derivative mode,
// outlier rule, column names), ols intervals, stepwise's kept terms, and a
// summary of the data (outliers removed, gaps, the window temperatures
// range temp_range_c, used by export for the firmware's TMIN/TMAX).
//
// With several gyro channels (--gyro-col gx,gy,gz) the file is
// {"channels": [{"channel": NAME, …the single-channel object…}, …]}.

#include <filesystem>
#include <map>
#include <optional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <utility>
#include <vector>

#include "fit/pipeline.h"

namespace gyrotherm::fit {

// (With data from `simulate`, studies/simulated.h adds the truth.)
// The `noise_model` object of fit's and diagnose's JSON (docs/contracts.md).
nlohmann::ordered_json noise_model_json(const NoiseModel& model);

nlohmann::ordered_json fit_json(const ModelFit& fit, const PreparedData& data,
                                const PipelineOptions& pipeline, const EngineSettings& settings);

// {"channels": [{"channel": name, ...object}, ...]}, the object's fields after
// "channel"; what fit, diagnose and compensate print for several channels.
nlohmann::ordered_json channels_json(
    const std::vector<std::pair<std::string, nlohmann::ordered_json>>& channels);

// The fit file's `pipeline` object and its parts, written by to_json and read
// back by from_json (nlohmann's hooks: `j["pipeline"] = options`,
// `j.get<PipelineOptions>()`). from_json throws InputError naming the field by
// its path in the object ("columns.csv.rate_hz: must be a finite number");
// Units' from_json leaves in each `*_from` only ", ORIGIN when fitting" (the
// loader puts the fit file's name before it, Units::set_from_fit) and does not
// validate.
void to_json(nlohmann::ordered_json& j, const CsvDialect& c);
void from_json(const nlohmann::json& j, CsvDialect& c);
void to_json(nlohmann::ordered_json& j, const Units& u);
void from_json(const nlohmann::json& j, Units& u);
void to_json(nlohmann::ordered_json& j, const ColumnMap& c);
void from_json(const nlohmann::json& j, ColumnMap& c);
void to_json(nlohmann::ordered_json& j, const PipelineOptions& p);
void from_json(const nlohmann::json& j, PipelineOptions& p);

struct SavedFit {
  std::filesystem::path file;
  std::string engine;
  std::vector<const Term*> terms;
  std::vector<double> parameters;
  Coefficients coefficients;
  PipelineOptions pipeline;
  double instability_after_dph = 0.0;
  std::optional<double> instability_before_dph;  // of the data it was fitted on (absent in hand-made files)
  std::string channel;  // the gyro column it was fitted to, in a several-channel file
  // The range of the window-mean temperatures it was fitted on (°C); absent in
  // fit files written before it was saved.
  std::optional<std::pair<double, double>> temp_range_c;
  std::string data_file;  // the data it was fitted on, as given to fit
  std::string data_sha256;  // its bytes' SHA-256 (hex; empty for a table, or a file written before it was saved)
  // Its numbers that looked like another unit (the fit's data.cautions, worded).
  std::vector<std::string> data_cautions;
  // Per term the record it was fitted on cannot support over its range, why
  // (fit/record_support.h: too few temperature levels, too narrow a range, a
  // gap with no data; not temperature locked to time, a caution of meaning).
  std::vector<std::pair<std::string, std::string>> support_flags;
  // Per term a caution of meaning only (temperature locked to time: the
  // number may be a drift's), which an export carries but does not stop on.
  std::vector<std::pair<std::string, std::string>> meaning_flags;
  // Of that data, for the real-time compensator (fit/causal_compensator.h):
  // the sample interval, the burst mode and the glitch rule's floor.
  std::optional<double> sample_interval_s, outlier_floor_dph;
  std::optional<bool> bursts;
};

// Which sensors' fits a reader takes (fit/data/sensor_kind.h): a gyro's
// only (compensate, check, report, allan --fit: refused with a message
// naming the fit's kind), or any (export).
enum class FitKinds { gyro, any };

// The sensor is the fit's (compensate, allan --fit): a --sensor given with it
// must name it; InputError otherwise, naming both.
void check_given_sensor(const SavedFit& fit, const std::string& given_sensor);

// Throws InputError naming the file and the field for anything missing or
// malformed, and for a fit whose top-level "sensor" contradicts its units'.
SavedFit load_fit(const std::filesystem::path& file);
// Every channel of a fit file: one for a single-channel file.
std::vector<SavedFit> load_fits(const std::filesystem::path& file, FitKinds kinds = FitKinds::gyro);
// The same, of a fit file's JSON already parsed (a Python FitResult's); `file`
// names it in messages and as SavedFit::file: kFitInMemory (fit/data/
// measurement.h) for a fit that was never a file (the units then come "from
// the fit given in memory").
std::vector<SavedFit> load_fits_json(const nlohmann::json& fit, const std::filesystem::path& file,
                                     FitKinds kinds = FitKinds::gyro);

}  // namespace gyrotherm::fit
