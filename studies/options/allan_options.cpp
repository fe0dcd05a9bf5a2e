#include "studies/options/allan_options.h"

#include <map>

namespace gyrotherm::studies {
// Named so that the unity batches can join the option files (each has its O).
namespace allan_rows_of {

using O = AllanCommandOptions;

std::vector<OptionRow<O>> allan_rows() {
  std::vector<OptionRow<O>> rows = {
      nested_row("data", "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log", &O::request, &AllanRequest::data,
                 true),
      nested_row("--fit", "Also the output compensated by this saved fit (as compensate --causal), side by side",
                 &O::request, &AllanRequest::fit_file),
      ruled_row<O>("--taus", "τ set: octave (1, 2, 4, … samples), decade, or all", &O::taus,
                   one_of({"octave", "decade", "all"})),
      defaulting(ruled_row<O>("--tau-max", "Longest τ in seconds (it needs a gap-free stretch of 2τ)",
                              [](O& o) -> auto& { return o.request.options.tau_max_s; }, number_in(0.0, kNoBound, "s")),
                 "a quarter of the record"),
      ruled_row<O>("--ci", "Confidence of the intervals (0.6827: ±1σ)",
                   [](O& o) -> auto& { return o.request.options.confidence; },
                   OptionRule{.kind = OptionRule::Kind::real, .lower = 0.0, .upper = 1.0, .lower_open = true,
                              .upper_open = true}),
      nested_row("--plot", "Write the log-log figure (PNG) with bands and the coefficients read", &O::request,
                 &AllanRequest::plot),
      field_row<O>("--json", "Print one JSON object", &O::json)};
  append_rows(rows, data_option_rows(false), &O::data_options);
  add_fit_file_defaults(rows, "with --fit");
  return rows;
}

}  // namespace allan_rows_of

const OptionTable<AllanCommandOptions>& allan_option_table() {
  static const OptionTable<AllanCommandOptions> table{"allan", allan_rows_of::allan_rows()};
  return table;
}

AllanRequest allan_request(const AllanCommandOptions& o) {
  static const std::map<std::string, TauSpacing> kSpacing = {
      {"octave", TauSpacing::octave}, {"decade", TauSpacing::decade}, {"all", TauSpacing::all}};
  check_rules(allan_option_table(), o);  // --taus, --tau-max, --ci
  AllanRequest request = o.request;
  AllanOptions& options = request.options;
  options.spacing = kSpacing.at(o.taus);
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
