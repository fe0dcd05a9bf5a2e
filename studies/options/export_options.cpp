#include "studies/options/export_options.h"

namespace gyrotherm::studies {

const OptionTable<ExportCommandOptions>& export_option_table() {
  using O = ExportCommandOptions;
  using R = ExportRequest;
  const auto row = [](const char* names, std::string help, auto field, bool required = false) {
    return nested_row(names, std::move(help), &O::request, field, required);
  };
  static const OptionTable<O> table{
      "export",
      {row("fit", "Fit saved by 'gyrotherm fit -o'", &R::fit_file, true),
       row("--format", "The format: " + exporter_descriptions(), &R::format, true),
       defaulting(row("--axes", "The fit's channels for the X, Y and Z axes, '-' for none", &R::axes), "the channels in order"),
       row("--channel", "The channel to export in C (--format c; px4 and ardupilot take every axis: --axes)", &R::channel),
       row("--prefix", "Prefix of the C names (--format c)", &R::prefix),
       defaulting(row("--instance",
           "Gyro instance: PX4's TC_G0..3, ArduPilot's IMU 1..5 (INS_TCAL1..3_, INS4/5_TCAL_)",
                      &R::instance),
                  "0 for PX4, 1 for ArduPilot"),
       row("--device-id", "PX4: the gyro's device id for TC_G{n}_ID (CAL_GYRO{n}_ID)", &R::device_id),
       defaulting(row("--boot-temp", "ArduPilot: the temperature (°C) the gyro offsets are taken at boot",
                      &R::boot_temp_c),
                  "the record's first"),
       row("--drop-unsupported", "Leave out terms the firmware cannot express, and say how much the instability rises",
           &R::drop_unsupported),
       row("--accept-caution",
           "Export even where the fit's record cannot support a term (too few temperature levels, a gap with no data, "
           "too narrow a range); the cautions go into the file",
           &R::accept_caution),
       defaulting(row("--data", "The data the fit was made on, for what the firmware achieves and --drop-unsupported",
                      &R::data),
                  "the fit's own"),
       row("--json", "Print one JSON object (what was written, and what the firmware achieves)", &R::json),
       row("-o,--output", "The parameter file to write", &R::output, true)}};
  return table;
}

ExportRequest export_request(const ExportCommandOptions& options) { return options.request; }

}  // namespace gyrotherm::studies
