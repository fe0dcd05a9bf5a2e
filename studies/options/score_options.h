#pragma once
// `gyrotherm score`'s options (sim/util/option_table.h) and the
// campaign they make (studies/score/campaign.h).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/util/option_table.h"
#include "studies/score/campaign.h"

namespace gyrotherm::studies {

struct ScoreCommandOptions {
  std::string scenario;
  std::string engines;  // comma-separated ("": every engine that minimises σ, all but gls)
  long trials = 100;
  int threads = 0;                     // per process (0: one per core; 1 under mpirun)
  std::optional<std::uint64_t> seed;   // absent: the scenario's
  std::string model = std::string(fit::kDefaultModel);
  std::vector<std::string> budgets;         // N or ENGINE=N
  std::vector<std::string> engine_options;  // ENGINE:KEY=VALUE
  std::string baseline;                     // a saved `score --json`
  std::string out;                          // the files' folder ("": none)
  bool json = false;
};

const OptionTable<ScoreCommandOptions>& score_option_table();

// The campaign's options; throws InputError for a --budget, an --option or a
// --threads out of its rule, naming it.
ScoreOptions score_request(const ScoreCommandOptions& options);

}  // namespace gyrotherm::studies
