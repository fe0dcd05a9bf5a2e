#include "studies/options/compensate_options.h"

#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {
// Named so that the unity batches can join the option files (each has its O).
namespace compensate_rows_of {

using O = CompensateCommandOptions;
using R = CompensateRequest;

std::vector<OptionRow<O>> compensate_rows() {
  std::vector<OptionRow<O>> rows = {
      nested_row("data", "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log", &O::request, &R::data, true),
      nested_row("--fit", "Fit saved by 'gyrotherm fit -o'", &O::request, &R::fit_file, true),
      nested_row("-o,--output", "Write time_s, temp_c, gyro_dph, model_dph, compensated_dph, outlier", &O::request,
                 &R::output),
      nested_row("--causal", "Real-time compensation: backward differences and only past windows", &O::request,
                 &R::causal),
      defaulting(nested_row("--extrapolate", "Evaluate the model outside the temperature range it was fitted on",
                            &O::request, &R::extrapolate),
                 "hold it at the range's edge, as the firmwares do"),
      field_row<O>("--json", "Print one JSON object", &O::json)};
  append_rows(rows, column_option_rows(/*fit_defaults=*/true), [](O& o) -> auto& { return o.request.columns; });
  return rows;
}

}  // namespace compensate_rows_of

const OptionTable<CompensateCommandOptions>& compensate_option_table() {
  static const OptionTable<CompensateCommandOptions> table{"compensate", compensate_rows_of::compensate_rows()};
  return table;
}

// Every sensor's fit: the sensor is the fit's (a --sensor given must say the same: compensate_run).
CompensateRequest compensate_request(const CompensateCommandOptions& o) { return o.request; }

}  // namespace gyrotherm::studies
