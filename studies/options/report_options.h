#pragma once
// `gyrotherm report`'s options (sim/util/option_table.h) and the
// request they make (studies/report/report.h).

#include "sim/util/option_table.h"
#include "studies/report/report.h"

namespace gyrotherm::studies {

struct ReportCommandOptions {
  ReportRequest request;
};

const OptionTable<ReportCommandOptions>& report_option_table();

// The request; throws InputError for --fit with --model or data options it would ignore.
ReportRequest report_request(const ReportCommandOptions& options);

}  // namespace gyrotherm::studies
