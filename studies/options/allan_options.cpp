#include "studies/options/allan_options.h"

#include <fmt/format.h>

#include <map>

#include "sim/util/input_error.h"

namespace gyrotherm::studies {
namespace {

using O = AllanCommandOptions;

std::vector<OptionRow<O>> allan_rows() {
  std::vector<OptionRow<O>> rows = {
      nested_row("data", "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log", &O::request, &AllanRequest::data,
                 true),
      nested_row("--fit", "Also the output compensated by this saved fit (as compensate --causal), side by side",
                 &O::request, &AllanRequest::fit_file),
      field_row<O>("--taus", "τ set: octave (1, 2, 4, … samples), decade, or all", &O::taus),
      defaulting(field_row<O>("--tau-max", "Longest τ in seconds (it needs a gap-free stretch of 2τ)",
                                [](O& o) -> auto& { return o.request.options.tau_max_s; }),
                 "a quarter of the record"),
      field_row<O>("--ci", "Confidence of the intervals, between 0 and 1 (0.6827: ±1σ)",
                   [](O& o) -> auto& { return o.request.options.confidence; }),
      nested_row("--plot", "Write the log-log figure (PNG) with bands and the coefficients read", &O::request,
                 &AllanRequest::plot),
      field_row<O>("--json", "Print one JSON object", &O::json)};
  append_rows(rows, data_option_rows(false), &O::data_options);
  add_fit_file_defaults(rows, "with --fit");
  return rows;
}

}  // namespace

const OptionTable<AllanCommandOptions>& allan_option_table() {
  static const OptionTable<O> table{"allan", allan_rows()};
  return table;
}

AllanRequest allan_request(const AllanCommandOptions& o) {
  static const std::map<std::string, TauSpacing> kSpacing = {
      {"octave", TauSpacing::octave}, {"decade", TauSpacing::decade}, {"all", TauSpacing::all}};
  const auto spacing = kSpacing.find(o.taus);
  if (spacing == kSpacing.end()) throw InputError(fmt::format("--taus {}: expected octave, decade or all", o.taus));
  AllanRequest request = o.request;
  AllanOptions& options = request.options;
  options.spacing = spacing->second;
  if (options.tau_max_s < 0.0)
    throw InputError(fmt::format("--tau-max {}: expected a positive time in seconds", options.tau_max_s));
  if (!(options.confidence > 0.0 && options.confidence < 1.0))
    throw InputError(
        fmt::format("--ci {}: the confidence must be between 0 and 1 (e.g. 0.68 or 0.95)", options.confidence));
  if (request.fit_file.empty()) {
    DataOptions data = o.data_options;
    data.pipeline.columns = fit::ColumnMap{}.with(data.pipeline.columns);
    request.pipeline = data.resolved();
  } else {
    request.fit_columns = o.data_options.pipeline.columns;  // laid over the fit's (compensate's rule)
  }
  return request;
}

}  // namespace gyrotherm::studies
