#pragma once
// The options shared by the commands that read measurements (fit, diagnose,
// allan; compensate the columns alone): column mapping, units, averaging
// window, derivative mode, outlier rule; and the model options of fit and
// diagnose. Their rows (sim/util/option_table.h) go into each
// command's table.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/util/option_table.h"

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

// Refuses a sensor other than a gyro (--sensor) for `command`: only `fit`
// reads an accelerometer's or a barometer's channel so far.
void require_gyro(const fit::ColumnMap& columns, std::string_view command);

// --avg (with_avg), --deriv-span, --causal, --keep-outliers,
// --outlier-threshold and the column options.
std::vector<OptionRow<DataOptions>> data_option_rows(bool with_avg = true);
// The data options a resolved pipeline differs from the defaults by, as a
// user would give them again (a next step's command or call).
std::vector<GivenOption> given_data_options(const fit::PipelineOptions& pipeline);
// The column and unit options alone; with fit_defaults the help says an
// unset option keeps the fit file's.
std::vector<OptionRow<fit::ColumnMap>> column_option_rows(bool fit_defaults);
// The column options among `rows` (a command that can also read a fit file's
// columns, as allan --fit and check with a fit file do): each default gains
// "; WHEN: the fit's" ("time_s; with --fit: the fit's").
template <class Options>
void add_fit_file_defaults(std::vector<OptionRow<Options>>& rows, const std::string& when) {
  for (const OptionRow<fit::ColumnMap>& c : column_option_rows(false))
    for (OptionRow<Options>& r : rows)
      if (r.names == c.names)
        r.default_note = (c.default_note.empty() ? std::string("off") : c.default_note) + "; " + when + ": the fit's";
}

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

// What fit and diagnose check, in the command line's order: the terms (the
// model and --add), the engine's name, its settings (`settings` makes them:
// fit's --budget, --target and --option are checked there), the engine's
// options, then the data options.
struct ModelRequest {
  std::vector<const fit::Term*> terms;
  fit::EngineSettings settings;
  fit::PipelineOptions pipeline;
};
ModelRequest model_request(const ModelOptions& model, const DataOptions& data,
                           const std::function<fit::EngineSettings()>& settings);

// The rows of a command that fits a model to a log (fit, diagnose), in the
// order its --help lists them: the log (`data`), the model options, the
// command's own rows, the data options. Options has the members data, model
// and data_options.
template <class Options>
std::vector<OptionRow<Options>> model_command_rows(const std::string& data_help, const std::string& add_help,
                                                   std::vector<OptionRow<Options>> own) {
  std::vector<OptionRow<Options>> rows = {field_row<Options>("data", data_help, &Options::data, true)};
  append_rows(rows, model_option_rows(add_help), &Options::model);
  rows.insert(rows.end(), own.begin(), own.end());
  append_rows(rows, data_option_rows(), &Options::data_options);
  return rows;
}

}  // namespace gyrotherm::studies
