#include "studies/options/compensate_options.h"

#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {

const OptionTable<CompensateCommandOptions>& compensate_option_table() {
  using O = CompensateCommandOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{"compensate", {}};
    auto& rows = t.rows;
    using R = CompensateRequest;
    rows.push_back(nested_row("data", "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log", &O::request, &R::data, true));
    rows.push_back(nested_row("--fit", "Fit saved by 'gyrotherm fit -o'", &O::request, &R::fit_file, true));
    rows.push_back(nested_row("-o,--output", "Write time_s, temp_c, gyro_dph, model_dph, compensated_dph, outlier",
                              &O::request, &R::output));
    rows.push_back(nested_row("--causal", "Real-time compensation: backward differences and only past windows",
                              &O::request, &R::causal));
    rows.push_back(field_row<O>("--json", "Print one JSON object", &O::json));
    append_rows(rows, column_option_rows(/*fit_defaults=*/true), [](O& o) -> auto& { return o.request.columns; });
    return t;
  }();
  return table;
}

CompensateRequest compensate_request(const CompensateCommandOptions& options) { return options.request; }

}  // namespace gyrotherm::studies
