#include "studies/options/report_options.h"

#include <fmt/format.h>

#include <filesystem>
#include <utility>

#include "fit/fit_file.h"
#include "sim/util/input_error.h"
#include "studies/options/pipeline_options.h"
#include "studies/report/report.h"
#include "studies/report/report_page.h"

#include <algorithm>

namespace gyrotherm::studies {
// Named so that the unity batches can join the option files (each has its O).
namespace report_rows_of {

using O = ReportCommandOptions;
using R = ReportRequest;

std::vector<OptionRow<O>> report_rows() {
  const auto row = [](const char* names, std::string help, auto field, bool required = false) {
    return nested_row(names, std::move(help), &O::request, field, required);
  };
  std::vector<OptionRow<O>> rows = {
      row("data", "The log: a measurement CSV, a PX4 ULog or an ArduPilot DataFlash log", &R::data, true),
      defaulting(row("--fit", "A fit saved by 'gyrotherm fit -o'", &R::fit_file),
                 "fit here with --model and the data options"),
      row("--params", "A calibration (PX4 .params, ArduPilot .parm or a fit file) to check on this log, as 'check'",
          &R::params),
      row("--max-residual", "With --params: PASS/FAIL against this residual against temperature, °/h",
          &R::max_residual_dph),
      row("--limits",
          "Acceptance limits judged on the page: residual=°/h (with --params), span=°C (at least), ratio=x (at least)",
          &R::limits),
      row("-o,--output", "The HTML page to write; its JSON twin goes beside it (.json)", &R::output, true)};
  append_rows(rows, model_option_rows("Append terms to the model fitted here"),
              [](O& o) -> auto& { return o.request.model; });
  append_rows(rows, data_option_rows(), [](O& o) -> auto& { return o.request.data_options; });
  return rows;
}

}  // namespace report_rows_of

ReportRequest report_request(const ReportCommandOptions& options) {
  const ReportRequest& r = options.request;
  require_gyro(r.data_options.pipeline.columns, "report");
  if (!r.fit_file.empty() && (r.model.model != ModelOptions().model || !r.model.add.empty()))
    throw InputError("report: --fit brings its own model; give --model (and --add) only without --fit");
  const std::vector<ReportLimit> limits = parse_limits(r.limits, r.max_residual_dph);  // refused here, before any work
  if (r.params.empty() && std::any_of(limits.begin(), limits.end(), [](const ReportLimit& l) { return l.name == "residual"; }))
    throw InputError("report: a residual limit (--max-residual, --limits residual=) judges the check of a calibration: "
                     "give it with --params");
  if (r.output.size() < 6 || r.output.substr(r.output.size() - 5) != ".html")
    throw InputError("report -o " + r.output + ": the page is HTML; name it FILE.html (its JSON twin is FILE.json)");
  // The page and its twin never replace an input (-o cal.html beside the fit
  // cal.json would write the twin over the fit).
  const std::string twin = report_twin_file(r.output);
  for (const auto& [option, input] : {std::pair{"the log", r.data}, {"--fit", r.fit_file}, {"--params", r.params}}) {
    std::error_code error;
    for (const std::string& written : {r.output, twin})
      if (!input.empty() && std::filesystem::equivalent(input, written, error))
        throw InputError(fmt::format("report -o {}: {} would be written over {} ({}); name the page otherwise "
                                     "(its JSON twin is the page's name with .json)",
                                     r.output, written, input, option));
  }
  if (!r.fit_file.empty()) fit::load_fits(r.fit_file);  // its errors (another sensor's fit) before any work
  return r;
}

const OptionTable<ReportCommandOptions>& report_option_table() {
  static const OptionTable<ReportCommandOptions> table{"report", report_rows_of::report_rows()};
  return table;
}

}  // namespace gyrotherm::studies
