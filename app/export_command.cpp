// gyrotherm export FIT.json --format c|px4|ardupilot [--channel NAME] [--prefix P]
//                           [--axes A,B,C] [--instance N] [--device-id ID] [--boot-temp C]
//                           [--drop-unsupported] [--data CSV] [--json] -o FILE
// A saved fit as firmware parameters or C (studies/export/exporter.h).

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "studies/export/exporter.h"

namespace gyrotherm::app {

void add_export_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<studies::ExportRequest>();
  CLI::App* cmd = app.add_subcommand("export", "Export a saved fit as autopilot parameters (PX4, ArduPilot) or C");
  cmd->add_option("fit", o->fit_file, "Fit saved by 'gyrotherm fit -o'")->required();
  cmd->add_option("--format", o->format, "The format: " + studies::exporter_descriptions())->required();
  cmd->add_option("--axes", o->axes,
                  "The fit's channels for the X, Y and Z axes, '-' for none (default: the channels in order)");
  cmd->add_option("--channel", o->channel, "The channel to export in C (--format c)");
  cmd->add_option("--prefix", o->prefix, "Prefix of the C names (--format c; default gt_comp)");
  cmd->add_option("--instance", o->instance,
                  "Gyro instance: PX4's TC_G0..3 (default 0), ArduPilot's IMU 1..5 (INS_TCAL1..3_, INS4/5_TCAL_; default 1)");
  cmd->add_option("--device-id", o->device_id, "PX4: the gyro's device id for TC_G{n}_ID (CAL_GYRO{n}_ID)");
  cmd->add_option("--boot-temp", o->boot_temp_c,
                  "ArduPilot: the temperature (°C) the gyro offsets are taken at boot (default: the record's first)");
  cmd->add_flag("--drop-unsupported", o->drop_unsupported,
                "Leave out terms the firmware cannot express, and say how much the instability rises");
  cmd->add_option("--data", o->data,
                  "The data the fit was made on, for what the firmware achieves and --drop-unsupported (default: the fit's own)");
  cmd->add_flag("--json", o->json, "Print one JSON object (what was written, and what the firmware achieves)");
  cmd->add_option("-o,--output", o->output, "The parameter file to write")->required();
  when_chosen(cmd, run, [o] {
    const studies::ExportOutput out = studies::run_export(*o);
    fmt::print("{}", o->json ? studies::export_json(*o, out).dump() + "\n" : studies::export_text(out));
    for (const std::string& warning : out.warnings) fmt::print(stderr, "gyrotherm: warning: {}\n", warning);
    return 0;
  });
}

}  // namespace gyrotherm::app
