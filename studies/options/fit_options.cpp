#include "studies/options/fit_options.h"

namespace gyrotherm::studies {

const OptionTable<FitCommandOptions>& fit_option_table() {
  using O = FitCommandOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{"fit", {}};
    t.rows.push_back(field_row<O>(
        "data", "Measurement CSV (time_s, temp_c, gyro_dph[, temp2_c]), or a PX4 / ArduPilot log", &O::data, true));
    append_rows(t.rows, model_option_rows("Add a term to the model (repeatable)"), &O::model);
    t.rows.push_back(field_row<O>("--budget", "Maximum objective evaluations (0: the engine's default)", &O::budget));
    t.rows.push_back(field_row<O>("--target", "Stop when sigma <= this, °/h (0: none)", &O::target));
    t.rows.push_back(field_row<O>("--option", "Engine option KEY=VALUE (repeatable)", &O::engine_options));
    t.rows.push_back(field_row<O>("-o,--output", "Save the fit as JSON (for compensate)", &O::output));
    t.rows.push_back(field_row<O>("--json", "Print the fit as one JSON object", &O::json));
    append_rows(t.rows, data_option_rows(), &O::data_options);
    return t;
  }();
  return table;
}

FitRequest fit_request(const FitCommandOptions& o) {
  FitRequest request;
  request.data = o.data;
  request.terms = o.model.terms();
  request.engine = o.model.engine;
  const fit::EngineInfo& engine = fit::find_engine(request.engine);  // its errors first, then the options'
  request.settings = fit::engine_settings(o.model.seed, o.budget, o.target, o.engine_options);
  engine.make(request.settings);
  request.pipeline = o.data_options.resolved();
  request.output = o.output;
  return request;
}

}  // namespace gyrotherm::studies
