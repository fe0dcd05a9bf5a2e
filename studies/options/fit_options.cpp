#include "studies/options/fit_options.h"

namespace gyrotherm::studies {

const OptionTable<FitCommandOptions>& fit_option_table() {
  using O = FitCommandOptions;
  static const OptionTable<O> table{
      "fit", model_command_rows<O>(
                 "Measurement CSV (time_s, temp_c, gyro_dph[, temp2_c]), or a PX4 / ArduPilot log",
                 "Add a term to the model (repeatable)",
                 {field_row<O>("--budget", "Maximum objective evaluations (0: the engine's default)", &O::budget),
                  field_row<O>("--target", "Stop when sigma <= this, °/h (0: none)", &O::target),
                  field_row<O>("--option", "Engine option KEY=VALUE (repeatable)", &O::engine_options),
                  field_row<O>("-o,--output", "Save the fit as JSON (for compensate)", &O::output),
                  field_row<O>("--json", "Print the fit as one JSON object", &O::json)})};
  return table;
}

FitRequest fit_request(const FitCommandOptions& o) {
  ModelRequest checked = model_request(o.model, o.data_options, [&] {
    return fit::engine_settings(o.model.seed, o.budget, o.target, o.engine_options);
  });
  FitRequest request;
  request.data = o.data;
  request.terms = std::move(checked.terms);
  request.engine = o.model.engine;
  request.settings = std::move(checked.settings);
  request.pipeline = std::move(checked.pipeline);
  request.output = o.output;
  return request;
}

}  // namespace gyrotherm::studies
