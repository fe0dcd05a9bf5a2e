#pragma once
// The options shared by the commands that read measurements (fit, diagnose,
// allan; compensate the columns alone): column mapping, units, averaging
// window, derivative mode, outlier rule; and the model options of fit and
// diagnose. Their rows (studies/options/option_table.h) go into each
// command's table.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "studies/options/option_table.h"

namespace gyrotherm::studies {

struct DataOptions {
  fit::PipelineOptions pipeline;
  bool causal = false;
  bool keep_outliers = false;
  std::optional<double> outlier_threshold;
  // The pipeline with the flags applied; throws InputError for contradicting
  // or out-of-range options (units, --outlier-threshold, --deriv-span).
  fit::PipelineOptions resolved() const;
};

// --avg (with_avg), --deriv-span, --causal, --keep-outliers,
// --outlier-threshold and the column options.
std::vector<OptionRow<DataOptions>> data_option_rows(bool with_avg = true);
// The column and unit options alone; with fit_defaults the help says an
// unset option keeps the fit file's.
std::vector<OptionRow<fit::ColumnMap>> column_option_rows(bool fit_defaults);

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

// --model, --add (`add_help` says what it does for the command), --engine, --seed.
std::vector<OptionRow<ModelOptions>> model_option_rows(const std::string& add_help);

}  // namespace gyrotherm::studies
