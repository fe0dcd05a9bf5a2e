#pragma once
// `gyrotherm reproduce`'s options (sim/util/option_table.h) and the
// run they make (studies/reproduce/reproduce.h).

#include <cstdint>
#include <string>

#include "sim/util/option_table.h"
#include "studies/reproduce/reproduce.h"

namespace gyrotherm::studies {

struct ReproduceCommandOptions {
  std::string out = "results";  // the report's folder
  std::string scenarios;        // the folder of cycle.toml, random.toml, warmup.toml ("": the default one)
  std::string engines;          // comma-separated ("": every engine that minimises σ, all but gls)
  std::uint64_t seed = 1;       // of the stochastic engines
  bool json = false;            // print table1.json rather than the text
};

const OptionTable<ReproduceCommandOptions>& reproduce_option_table();

// The run: the three scenarios of `scenarios`, or of `default_scenarios` when
// none is given (the progress is the caller's to set).
ReproduceOptions reproduce_request(const ReproduceCommandOptions& options, const std::string& default_scenarios);

}  // namespace gyrotherm::studies
