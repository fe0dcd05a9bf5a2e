#pragma once
// The report's JSON twin (every number the page shows) and the page itself,
// rendered from the twin: each table cell carries the JSON pointer of its
// number (data-json), so the page and the twin cannot disagree.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fit/fit_file.h"
#include "studies/allan/allan_study.h"
#include "studies/check/check_run.h"
#include "studies/fit/compensate_run.h"
#include "studies/report/report.h"
#include "studies/report/report_evidence.h"

namespace gyrotherm::studies {

// One channel's figures, as data: URIs (PNG, base64).
struct ChannelFigures {
  std::string bias, time, allan;
};

struct ReportContent {
  nlohmann::ordered_json twin;
  std::string temperature;                // the record's temperature figure
  std::vector<ChannelFigures> channels;   // in the twin's channel order
};

// A user's acceptance limit (--limits NAME=VALUE, --max-residual as residual).
struct ReportLimit {
  std::string name;  // residual, span, ratio
  double value = 0.0;
};
// Throws InputError for an unknown name, a value that is no number above 0, a name twice.
std::vector<ReportLimit> parse_limits(const std::string& text, std::optional<double> max_residual_dph);
// Each limit judged on the twin's numbers: [{name, limit, value, passed}].
nlohmann::ordered_json judged_limits(const std::vector<ReportLimit>& limits, const nlohmann::ordered_json& twin);

nlohmann::ordered_json report_twin(const ReportRequest& request, const std::vector<fit::SavedFit>& fits,
                                   const nlohmann::ordered_json& fit_json, const CompensateRun& compensated,
                                   const std::vector<AllanStudy>& allan, const nlohmann::ordered_json& diagnosis,
                                   const std::optional<CheckResult>& check, const std::vector<ChannelBand>& bands);

// The self-contained HTML page (inline CSS with a print stylesheet, no scripts).
std::string report_html(const ReportContent& content);

}  // namespace gyrotherm::studies
