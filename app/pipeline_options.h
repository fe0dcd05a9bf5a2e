#pragma once
// Command-line options shared by the commands that read measurements (fit,
// compensate, diagnose): column mapping, averaging window, derivative mode,
// outlier rule.

#include <optional>

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

}  // namespace gyrotherm::app
