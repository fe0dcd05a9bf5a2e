#include "studies/score/baseline.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/util/input_error.h"
#include "sim/util/numbers.h"

namespace gyrotherm::studies {

namespace {

using Json = nlohmann::ordered_json;

struct MetricRule {
  bool higher_is_worse;
  bool clip_at_target;  // values ≤ ε are all "at the optimum"
};

MetricRule rule_of(const std::string& metric) {
  if (metric == "success_rate" || metric == "ratio_median") return {false, false};
  if (metric == "gap_median") return {true, true};
  return {true, false};  // evals_to_target_median, coefficient_error_median.<term>
}

[[noreturn]] void bad(const std::string& where, const std::string& field, const std::string& expected) {
  throw InputError(fmt::format("{}: {}: expected {} (a saved 'gyrotherm score --json')", where, field, expected));
}

double read_bound(const Json& v, const std::string& where, const std::string& field) {
  if (v.is_null()) return kInfinity;  // "not reached"
  if (!v.is_number()) bad(where, field, "a number or null");
  return v.get<double>();
}

BaselineMetric read_metric(const Json& value, const Json& ci, const std::string& where,
                           const std::string& field, const std::string& ci_field) {
  BaselineMetric m;
  m.value = read_bound(value, where, field);
  if (!ci.is_array() || ci.size() != 2) bad(where, ci_field, "[low, high]");
  m.ci = {read_bound(ci[0], where, ci_field + "[0]"), read_bound(ci[1], where, ci_field + "[1]")};
  return m;
}

const Json& member(const Json& j, const std::string& key, const std::string& where, const std::string& path,
                   const std::string& expected) {
  if (!j.is_object() || !j.contains(key)) bad(where, path, expected);
  return j.at(key);
}

}  // namespace

Baseline parse_baseline(std::string_view text, const std::string& where) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", where, e.what()));
  }
  Baseline b;
  b.file = where;
  const Json& model = member(j, "model", where, "model", "a string");
  if (!model.is_string()) bad(where, "model", "a string");
  b.model = model.get<std::string>();
  const Json& target = member(j, "target_relative", where, "target_relative", "a number");
  if (!target.is_number()) bad(where, "target_relative", "a number");
  b.target_relative = target.get<double>();
  const Json& trials = member(j, "trials", where, "trials", "a whole number");
  if (!trials.is_number_unsigned()) bad(where, "trials", "a whole number");
  b.trials = trials.get<std::size_t>();
  if (j.contains("scenario") && j["scenario"].is_string()) b.scenario = j["scenario"].get<std::string>();
  if (j.contains("file_sha256") && j["file_sha256"].is_object())
    for (const auto& [k, v] : j["file_sha256"].items())
      if (v.is_string()) b.file_sha256[k] = v.get<std::string>();
  const Json& engines = member(j, "engines", where, "engines", "an object (engine -> scores)");
  if (!engines.is_object()) bad(where, "engines", "an object (engine -> scores)");
  for (const auto& [name, e] : engines.items()) {
    const std::string at = "engines." + name;
    const Json& ci = member(e, "ci95", where, at + ".ci95", "an object of 95 % intervals");
    auto& metrics = b.engines[name];
    for (const char* metric : {"success_rate", "evals_to_target_median", "gap_median", "ratio_median"})
      metrics[metric] = read_metric(member(e, metric, where, at + "." + metric, "a number or null"),
                                    member(ci, metric, where, at + ".ci95." + metric, "[low, high]"), where,
                                    at + "." + metric, at + ".ci95." + metric);
    const Json& errors = member(e, "coefficient_error_median", where, at + ".coefficient_error_median",
                                "an object (term -> value)");
    const Json& errors_ci = member(ci, "coefficient_error_median", where, at + ".ci95.coefficient_error_median",
                                   "an object (term -> [low, high])");
    if (!errors.is_object()) bad(where, at + ".coefficient_error_median", "an object (term -> value)");
    for (const auto& [term, v] : errors.items())
      metrics["coefficient_error_median." + term] =
          read_metric(v, member(errors_ci, term, where, at + ".ci95.coefficient_error_median." + term, "[low, high]"),
                      where, at + ".coefficient_error_median." + term,
                      at + ".ci95.coefficient_error_median." + term);
  }
  return b;
}

Baseline load_baseline(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(fmt::format("{}: no such file (a saved 'gyrotherm score --json')", file.string()));
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return parse_baseline(s.str(), file.string());
}

std::map<std::string, BaselineMetric> checked_metrics(const Scoreboard& board, const EngineScore& e) {
  std::map<std::string, BaselineMetric> m;
  m["success_rate"] = {e.success_rate, e.success_ci};
  m["evals_to_target_median"] = {e.evaluations_to_target.median, e.evaluations_to_target.median_ci};
  m["gap_median"] = {e.gap.median, e.gap.median_ci};
  m["ratio_median"] = {e.ratio.median, e.ratio.median_ci};
  for (std::size_t k = 0; k < board.error_terms.size(); ++k)
    m["coefficient_error_median." + board.error_terms[k]] = {e.coefficient_error[k].median,
                                                            e.coefficient_error[k].median_ci};
  return m;
}

std::string regression_text(const Regression& r) {
  return fmt::format("{}: {} = {} (95 % interval {}..{}) is {} the baseline's {} ({}..{}), beyond Monte Carlo noise",
                     r.engine, r.metric, format_value(r.now.value, "{:.4g}"), format_value(r.now.ci.low, "{:.4g}"),
                     format_value(r.now.ci.high, "{:.4g}"), r.higher_is_worse ? "above" : "below",
                     format_value(r.baseline.value, "{:.4g}"), format_value(r.baseline.ci.low, "{:.4g}"),
                     format_value(r.baseline.ci.high, "{:.4g}"));
}

std::string baseline_note_text(const BaselineNote& n) {
  switch (n.kind) {
    case BaselineNote::Kind::file_changed:
      return fmt::format("the baseline was made with another {} file (SHA-256 differs); if it changed on purpose, "
                         "make the baseline again",
                         n.name);
    case BaselineNote::Kind::engine_missing: return fmt::format("no baseline for engine '{}'", n.name);
    case BaselineNote::Kind::metric_missing: return fmt::format("{}: no baseline for {}", n.name, n.metric);
  }
  return {};
}

BaselineComparison compare_to_baseline(const Scoreboard& current, const Baseline& baseline) {
  if (baseline.model != current.model)
    throw InputError(fmt::format("{}: made for the model '{}', this campaign fits '{}'", baseline.file,
                                 baseline.model, current.model));
  if (baseline.target_relative != current.target_relative)
    throw InputError(fmt::format("{}: made with the target optimum·(1 + {:g}), this campaign uses {:g}",
                                 baseline.file, baseline.target_relative, current.target_relative));
  BaselineComparison out;
  for (const auto& [file, sha] : current.file_sha256) {
    const auto it = baseline.file_sha256.find(file);
    if (it != baseline.file_sha256.end() && it->second != sha)
      out.notes.push_back({BaselineNote::Kind::file_changed, file, {}});
  }
  const double eps = current.target_relative;
  for (const EngineScore& e : current.engines) {
    const auto base = baseline.engines.find(e.engine);
    if (base == baseline.engines.end()) {
      out.notes.push_back({BaselineNote::Kind::engine_missing, e.engine, {}});
      continue;
    }
    for (const auto& [metric, now] : checked_metrics(current, e)) {
      const auto b = base->second.find(metric);
      if (b == base->second.end()) {
        out.notes.push_back({BaselineNote::Kind::metric_missing, e.engine, metric});
        continue;
      }
      const MetricRule rule = rule_of(metric);
      Range c = now.ci, r = b->second.ci;
      if (rule.clip_at_target) {
        c = {std::max(c.low, eps), std::max(c.high, eps)};
        r = {std::max(r.low, eps), std::max(r.high, eps)};
      }
      // A relative slack of 1e-9 keeps last-bit differences between machines out.
      const bool worse = rule.higher_is_worse
                             ? std::isfinite(r.high) && c.low > r.high + 1e-9 * std::abs(r.high)
                             : std::isfinite(r.low) && c.high < r.low - 1e-9 * std::abs(r.low);
      if (!worse) continue;
      out.regressions.push_back({e.engine, metric, now, b->second, rule.higher_is_worse});
    }
  }
  return out;
}

}  // namespace gyrotherm::studies
