#include "studies/options/reproduce_options.h"

#include "sim/util/comma_list.h"

namespace gyrotherm::studies {

const OptionTable<ReproduceCommandOptions>& reproduce_option_table() {
  using O = ReproduceCommandOptions;
  static const OptionTable<O> table{
      "reproduce",
      {field_row<O>("--out", "Output folder", &O::out),
       defaulting(field_row<O>("--scenarios", "Folder with cycle.toml, random.toml, warmup.toml", &O::scenarios),
                  "scenarios/"),
       defaulting(field_row<O>("--engines", "Comma-separated engines", &O::engines),
                  "every engine that minimises σ (all but gls)"),
       field_row<O>("--seed", "Seed of the stochastic engines", &O::seed),
       field_row<O>("--json", "Print table1.json, with the run times, on stdout", &O::json)}};
  return table;
}

ReproduceOptions reproduce_request(const ReproduceCommandOptions& options, const std::string& default_scenarios) {
  const std::string dir = options.scenarios.empty() ? default_scenarios : options.scenarios;
  ReproduceOptions r;
  r.cycle = dir + "/cycle.toml";
  r.test1 = dir + "/random.toml";
  r.test2 = dir + "/warmup.toml";
  r.engines = split_commas(options.engines);
  r.engine_seed = options.seed;
  return r;
}

}  // namespace gyrotherm::studies
