// gyrotherm export FIT.json --format c|px4|ardupilot [--channel NAME] [--prefix P]
//                           [--axes A,B,C] [--instance N] [--device-id ID] [--boot-temp C]
//                           [--drop-unsupported] [--data CSV] [--json] -o FILE
// A saved fit as firmware parameters or C (studies/options/export_options.h, studies/export/exporter.h).

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/export_options.h"

namespace gyrotherm::app {

void add_export_command(CLI::App& app, Run* run) {
  add_table_command<studies::ExportCommandOptions>(app, run, "export", "Export a saved fit as autopilot parameters (PX4, ArduPilot) or C",
      studies::export_option_table(), [](const auto& o) {
    const studies::ExportRequest request = studies::export_request(o);
    const studies::ExportOutput out = studies::run_export(request);
    fmt::print("{}", request.json ? studies::export_json(request, out).dump() + "\n" : studies::export_text(out));
    for (const std::string& warning : out.warnings) fmt::print(stderr, "gyrotherm: warning: {}\n", warning);
    return 0;
  });
}

}  // namespace gyrotherm::app
