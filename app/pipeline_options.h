#pragma once
// Command-line options shared by the commands that read measurements (fit,
// diagnose, allan): column mapping, units, averaging window, derivative mode,
// outlier rule; and the model options of fit and diagnose.

#include <optional>

#include <cstdint>
#include <string>
#include <vector>

#include "fit/model/formula.h"

#include "fit/pipeline.h"

namespace CLI {
class App;
}

namespace gyrotherm::app {

struct DataOptions {
  fit::PipelineOptions pipeline;
  bool causal = false;
  bool keep_outliers = false;
  std::optional<double> outlier_threshold;
  // Applies the flags to pipeline (call after parsing).
  fit::PipelineOptions resolved() const;
};

void add_data_options(CLI::App* command, DataOptions& options, bool with_avg = true);
// The column and unit options alone (part of add_data_options); with
// fit_defaults the help says an unset option keeps the fit file's.
void add_column_options(CLI::App* command, fit::ColumnMap& columns, bool fit_defaults);

// The model and engine options shared by fit and diagnose.
struct ModelOptions {
  std::string model = std::string(fit::kDefaultModel);
  std::vector<std::string> add;  // terms appended with --add
  std::string engine = "ols";
  std::uint64_t seed = 1;
  // The terms of --model alone, and with the --add terms after them.
  std::vector<const fit::Term*> base_terms() const;
  std::vector<const fit::Term*> terms() const;
};

// `add_help` says what --add does for this command.
void add_model_options(CLI::App* command, ModelOptions& options, const std::string& add_help);

}  // namespace gyrotherm::app
