#include "studies/options/check_options.h"

#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {
namespace {

using O = CheckCommandOptions;
using R = CheckRequest;

std::vector<OptionRow<O>> check_rows() {
  const auto row = [](const char* names, std::string help, auto field, bool required = false) {
    return nested_row(names, std::move(help), &O::request, field, required);
  };
  std::vector<OptionRow<O>> rows = {
      row("log", "The second log: a PX4 ULog, an ArduPilot DataFlash log or a measurement CSV", &R::log, true),
      row("--params",
          "The calibration: PX4 .params, ArduPilot .parm (as exported or as their own tools write them), or a fit file",
          &R::parameters, true),
      row("--max-residual",
          "Fail (exit 1) when an axis's residual against temperature exceeds this (in --residual-unit)",
          &R::max_residual),
      row("--residual-unit", "Unit of --max-residual: dph, dps, rad/s or mrad/s (default dph)", &R::residual_unit),
      row("--avg", "Window of the instability, s (default 100; a tenth of a shorter log)", &R::avg_s),
      row("--boot", "ArduPilot: the boot gyro calibration, the log's first seconds (default 10)", &R::boot_s),
      field_row<O>("--json", "Print one JSON object", &O::json)};
  append_rows(rows, column_option_rows(/*fit_defaults=*/false), [](O& o) -> auto& { return o.request.columns; });
  return rows;
}

}  // namespace

const OptionTable<CheckCommandOptions>& check_option_table() {
  static const OptionTable<O> table{"check", check_rows()};
  return table;
}

CheckRequest check_request(const CheckCommandOptions& options) { return options.request; }

}  // namespace gyrotherm::studies
