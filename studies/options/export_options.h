#pragma once
// `gyrotherm export`'s options (sim/util/option_table.h) and the
// request they make (studies/export/exporter.h).

#include "studies/export/exporter.h"
#include "sim/util/option_table.h"

namespace gyrotherm::studies {

struct ExportCommandOptions {
  ExportRequest request;  // every option, --json too
};

const OptionTable<ExportCommandOptions>& export_option_table();

// The request (run_export checks the format and its options).
ExportRequest export_request(const ExportCommandOptions& options);

}  // namespace gyrotherm::studies
