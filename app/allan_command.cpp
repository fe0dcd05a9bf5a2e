// gyrotherm allan DATA.csv [--fit FIT.json] [--taus octave|decade|all] [--tau-max S]
//                          [--ci C] [--plot PNG] [--json]
// (studies/options/allan_options.h, studies/allan/allan_study.h)

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/allan_options.h"

namespace gyrotherm::app {

void add_allan_command(CLI::App& app, Run* run) {
  CLI::App* cmd = add_subcommand(
      app, "allan",
      "Allan deviation with intervals and noise coefficients, before and after compensation");
  bind_command<studies::AllanCommandOptions>(cmd, run, studies::allan_option_table(), [](const auto& o) {
    const std::vector<studies::AllanStudy> studies = studies::run_allan(studies::allan_request(o));
    fmt::print("{}", o.json ? studies::allan_json(studies).dump() + "\n" : studies::allan_text(studies));
    return 0;
  });
}

}  // namespace gyrotherm::app
