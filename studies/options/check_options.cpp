#include "studies/options/check_options.h"

#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {
// Named so that the unity batches can join the option files (each has its O).
namespace check_rows_of {

using O = CheckCommandOptions;
using R = CheckRequest;

// The log and calibration, the verdict's limit and unit, the windows, then
// the column and unit options of a CSV log.
std::vector<OptionRow<O>> check_rows() {
  std::vector<OptionRow<O>> rows{
      nested_row("log", "The second log: a PX4 ULog, an ArduPilot DataFlash log or a measurement CSV", &O::request, &R::log, true),
      nested_row("--params",
          "The calibration: PX4 .params, ArduPilot .parm (as exported or as their own tools write them), or a fit file",
          &O::request, &R::parameters, true),
      nested_row("--max-residual",
          "Fail (exit 1) when an axis's residual against temperature exceeds this (in --residual-unit)",
          &O::request, &R::max_residual),
      nested_row("--residual-unit", "Unit of --max-residual: dph, dps, rad/s or mrad/s (another sensor's: one of its own, e.g. mps2, mg, Pa)", &O::request, &R::residual_unit),
      nested_row("--avg", "Window of the instability, s (a tenth of a log shorter than 10 windows)", &O::request, &R::avg_s),
      nested_row("--boot", "ArduPilot: the boot gyro calibration, the log's first seconds", &O::request, &R::boot_s),
      field_row<O>("--json", "Print one JSON object", &O::json)};
  append_rows(rows, column_option_rows(/*fit_defaults=*/false), [](O& o) -> auto& { return o.request.columns; });
  add_fit_file_defaults(rows, "with a fit file as --params");
  for (OptionRow<O>& r : rows) {
    if (r.names == "--imu") r.default_note = "the one the calibration is for";
    if (r.names == "--residual-unit") r.default_note = "dph (another sensor's: its base unit)";
    // A CSV log checked against a PX4 or ArduPilot file is read as three axes (check_run.cpp's read_csv).
    if (r.names == "--gyro-col") r.default_note = "gyro_x,gyro_y,gyro_z (another sensor's: by role); with a fit file as --params: the fit's";
  }
  return rows;
}

}  // namespace check_rows_of

CheckRequest check_request(const CheckCommandOptions& options) { return options.request; }

const OptionTable<CheckCommandOptions>& check_option_table() {
  static const OptionTable<CheckCommandOptions> table{"check", check_rows_of::check_rows()};
  return table;
}

}  // namespace gyrotherm::studies
