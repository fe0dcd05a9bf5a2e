#include "studies/options/allan_options.h"

#include <fmt/format.h>

#include <map>
#include <tuple>

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
      field_row<O>("--taus", "τ set: octave (default: 1, 2, 4, … samples), decade, or all", &O::taus),
      field_row<O>("--tau-max", "Longest τ in seconds (default a quarter of the record; it needs a gap-free stretch of 2τ)",
                   [](O& o) -> auto& { return o.request.options.tau_max_s; }),
      field_row<O>("--ci", "Confidence of the intervals, between 0 and 1 (default 0.683, ±1σ)",
                   [](O& o) -> auto& { return o.request.options.confidence; }),
      nested_row("--plot", "Write the log-log figure (PNG) with bands and the coefficients read", &O::request,
                 &AllanRequest::plot),
      field_row<O>("--json", "Print one JSON object", &O::json)};
  append_rows(rows, data_option_rows(false), &O::data_options);
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
    request.pipeline = o.data_options.resolved();
  } else {
    // With a fit, the fit's columns and units, but for those the options name
    // (the ones that differ from the defaults: a log whose columns differ from
    // the fit's). Giving a default's own name keeps the fit's.
    const fit::ColumnMap& c = o.data_options.pipeline.columns;
    const fit::ColumnMap d;
    fit::ColumnMap& given = request.fit_columns;
    for (auto [mine, theirs, dflt] : {std::tuple{&given.time, &c.time, &d.time}, {&given.temp, &c.temp, &d.temp},
                                      {&given.gyro, &c.gyro, &d.gyro}, {&given.temp2, &c.temp2, &d.temp2},
                                      {&given.units.time, &c.units.time, &d.units.time},
                                      {&given.units.gyro, &c.units.gyro, &d.units.gyro},
                                      {&given.units.temp, &c.units.temp, &d.units.temp}})
      if (*theirs != *dflt) *mine = *theirs;
    for (auto [mine, theirs, dflt] : {std::tuple{&given.units.gyro_scale, c.units.gyro_scale, d.units.gyro_scale},
                                      {&given.units.temp_scale, c.units.temp_scale, d.units.temp_scale},
                                      {&given.units.temp_offset, c.units.temp_offset, d.units.temp_offset}})
      if (theirs != dflt) *mine = theirs;
  }
  return request;
}

}  // namespace gyrotherm::studies
