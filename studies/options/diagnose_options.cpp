#include "studies/options/diagnose_options.h"

#include "sim/util/comma_list.h"

namespace gyrotherm::studies {

const OptionTable<DiagnoseCommandOptions>& diagnose_option_table() {
  using O = DiagnoseCommandOptions;
  static const OptionTable<O> table{
      "diagnose",
      model_command_rows<O>(
          "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log", "Add a term and compare before/after (repeatable)",
          {field_row<O>("--candidates",
                        "Candidates to try: a comma list (terms, columns, 'step'), or +NAME/-NAME to add to or "
                        "remove from the default set (every other term, every numeric column, the steps found)",
                        &O::candidates),
           field_row<O>("--plots", "Write PNG figures into this folder", &O::plots),
           field_row<O>("--json", "Print one JSON object", &O::json)})};
  return table;
}

DiagnoseRequest diagnose_request(const DiagnoseCommandOptions& o) {
  DiagnoseRequest request;
  request.data = o.data;
  request.base_terms = o.model.base_terms();
  ModelRequest checked = model_request(o.model, o.data_options, [&] { return fit::EngineSettings{.seed = o.model.seed}; });
  request.terms = std::move(checked.terms);
  request.added = o.model.add;
  request.engine = o.model.engine;
  request.settings = std::move(checked.settings);
  request.pipeline = std::move(checked.pipeline);
  request.options.candidates = split_commas(o.candidates);
  request.plots = o.plots;
  return request;
}

}  // namespace gyrotherm::studies
