#include "studies/options/score_options.h"

#include "sim/util/comma_list.h"

namespace gyrotherm::studies {

const OptionTable<ScoreCommandOptions>& score_option_table() {
  using O = ScoreCommandOptions;
  static const OptionTable<O> table{
      "score",
      {field_row<O>("scenario", "Scenario TOML (its [spread] table, if any, varies the gyro per trial)", &O::scenario,
                    true),
       defaulting(field_row<O>("--engines", "Comma-separated engines", &O::engines),
                  "every engine that minimises σ (all but gls)"),
       field_row<O>("--trials", "Number of trials N", &O::trials),
       defaulting(ruled_row<O>("--threads", "Threads per process", &O::threads,
                               whole_or_zero(1, 1024, "one per core")),
                  "one per core; 1 under mpirun"),
       defaulting(field_row<O>("--seed", "Campaign seed S; trial k uses S + k", &O::seed), "the scenario's seed"),
       field_row<O>("--model", "Model formula", &O::model),
       field_row<O>("--budget",
                    "Evaluation budget: N for every seeded engine, or ENGINE=N (repeatable; 0: the engine's default)",
                    &O::budgets),
       field_row<O>("--option", "Engine option ENGINE:KEY=VALUE (repeatable)", &O::engine_options),
       field_row<O>("--baseline",
                    "A saved 'score --json': exit 1 naming engine and metric where an engine is worse beyond "
                    "Monte Carlo noise",
                    &O::baseline),
       defaulting(field_row<O>("--out",
                               "Write scoreboard.json, scoreboard.md, convergence.csv and convergence.png here",
                               &O::out),
                  "no files"),
       field_row<O>("--json", "Print the scoreboard as one JSON object", &O::json)}};
  return table;
}

ScoreOptions score_request(const ScoreCommandOptions& o) {
  check_rules(score_option_table(), o);  // --threads
  ScoreOptions s;
  s.scenario = o.scenario;
  s.engines = split_commas(o.engines);
  s.model = o.model;
  s.trials = o.trials;
  s.seed = o.seed;
  for (const std::string& b : o.budgets) s.add_budget(b);
  for (const std::string& kv : o.engine_options) s.add_engine_option(kv);
  return s;
}

}  // namespace gyrotherm::studies
