#pragma once
// The fit's JSON: what `fit --json` prints and `fit -o FIT.json` saves, and
// what `compensate --fit FIT.json` reads back. Fields (DESIGN.md): engine,
// model, coefficients (term → value, the intercept under "1"),
// instability_before_dph, instability_after_dph, ratio, objective,
// evaluations, iterations, seconds, termination, history; with data from
// `simulate`, truth and coefficient_error. Also saved, for compensate:
// parameters of nonlinear terms, the pipeline (window, derivative mode,
// outlier rule, column names), ols intervals, stepwise's kept terms, and a
// summary of the data (outliers removed, gaps).

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "fit/pipeline.h"

namespace gyrotherm::fit {

std::string fit_json_text(const ModelFit& fit, const PreparedData& data,
                          const PipelineOptions& pipeline, const EngineSettings& settings,
                          const std::optional<Truth>& truth);

struct SavedFit {
  std::filesystem::path file;
  std::string engine;
  std::vector<const Term*> terms;
  std::vector<double> parameters;
  Coefficients coefficients;
  PipelineOptions pipeline;
  double instability_after_dph = 0.0;
};

// Throws InputError naming the file and the field for anything missing or malformed.
SavedFit load_fit(const std::filesystem::path& file);

}  // namespace gyrotherm::fit
