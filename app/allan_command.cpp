// gyrotherm allan DATA.csv [--fit FIT.json] [--taus octave|decade|all] [--tau-max S]
//                          [--ci C] [--plot PNG] [--json]
// (studies/options/allan_options.h, studies/allan/allan_study.h)

#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/allan_options.h"

namespace gyrotherm::app {

void add_allan_command(CLI::App& app, Run* run) {
  add_table_command<studies::AllanCommandOptions>(app, run, "allan", "Allan deviation with intervals and noise coefficients, before and after compensation",
      studies::allan_option_table(), [](const auto& o) {
    const std::vector<studies::AllanStudy> studies = studies::run_allan(studies::allan_request(o));
    return print_report(o.json, studies::allan_json(studies), studies::allan_text(studies));
  });
}

}  // namespace gyrotherm::app
