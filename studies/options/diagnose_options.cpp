#include "studies/options/diagnose_options.h"

#include "sim/util/comma_list.h"

namespace gyrotherm::studies {

const OptionTable<DiagnoseCommandOptions>& diagnose_option_table() {
  using O = DiagnoseCommandOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{"diagnose", {}};
    t.rows.push_back(field_row<O>("data", "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log", &O::data, true));
    append_rows(t.rows, model_option_rows("Add a term and compare before/after (repeatable)"), &O::model);
    t.rows.push_back(field_row<O>("--candidates",
                                  "Candidates to try: a comma list (terms, columns, 'step'), or +NAME/-NAME to add to or "
                                  "remove from the default set (every other term, every numeric column, the steps found)",
                                  &O::candidates));
    t.rows.push_back(field_row<O>("--plots", "Write PNG figures into this folder", &O::plots));
    t.rows.push_back(field_row<O>("--json", "Print one JSON object", &O::json));
    append_rows(t.rows, data_option_rows(), &O::data_options);
    return t;
  }();
  return table;
}

DiagnoseRequest diagnose_request(const DiagnoseCommandOptions& o) {
  DiagnoseRequest request;
  request.data = o.data;
  request.base_terms = o.model.base_terms();
  request.terms = o.model.terms();
  request.added = o.model.add;
  request.engine = o.model.engine;
  request.settings.seed = o.model.seed;
  fit::find_engine(request.engine).make(request.settings);  // the engine's errors before the data options'
  request.pipeline = o.data_options.resolved();
  request.options.candidates = split_commas(o.candidates);
  request.plots = o.plots;
  return request;
}

}  // namespace gyrotherm::studies
