#include "studies/diagnose/report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>
#include <nlohmann/json.hpp>

#include "fit/fit_file.h"
#include "fit/model/formula.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {
namespace {

// Times since the record's start, and on the log's own clock.
nlohmann::ordered_json segment_json(const SegmentReport& s, double start_time_s) {
  return {{"kind", to_string(s.kind)},
          {"start_s", s.start_s},
          {"end_s", s.end_s},
          {"log_start_s", s.start_s + start_time_s},
          {"log_end_s", s.end_s + start_time_s},
          {"temp_min_c", s.temp_min_c},
          {"temp_max_c", s.temp_max_c},
          {"windows", s.windows},
          {"rms_dph", s.rms_dph},
          {"ratio_to_floor", s.ratio_to_floor}};
}

const char* reason_name(ConfoundingReason r) {
  switch (r) {
    case ConfoundingReason::temperature_follows_time: return "temperature_follows_time";
    case ConfoundingReason::constant_rate: return "constant_rate";
    case ConfoundingReason::settling_curve: return "settling_curve";
    case ConfoundingReason::narrow_range: return "narrow_range";
    case ConfoundingReason::lag_follows_temperature: return "lag_follows_temperature";
    case ConfoundingReason::proportional: return "proportional";
    case ConfoundingReason::same_part: return "same_part";
    case ConfoundingReason::encompasses: return "encompasses";
  }
  return "";
}

const char* verdict_name(VerdictKind k) {
  switch (k) {
    case VerdictKind::nothing_to_try: return "nothing_to_try";
    case VerdictKind::found: return "found";
    case VerdictKind::group: return "group";
    case VerdictKind::none: return "none";
  }
  return "";
}

nlohmann::ordered_json group_json(const ConfoundingGroup& g) {
  nlohmann::ordered_json evidence = nlohmann::ordered_json::array();
  for (const ConfoundingEvidence& e : g.evidence) {
    nlohmann::ordered_json j = {{"reason", reason_name(e.reason)}};
    switch (e.reason) {
      case ConfoundingReason::temperature_follows_time:
        j["correlation"] = e.correlation;
        j["direction"] = e.direction == Direction::cools ? "cools" : e.direction == Direction::heats ? "heats" : "both";
        break;
      case ConfoundingReason::constant_rate: j["rate_c_per_h"] = e.rate_c_per_h; break;
      case ConfoundingReason::narrow_range: j["temp_range_c"] = {e.temp_min_c, e.temp_max_c}; break;
      case ConfoundingReason::lag_follows_temperature: j["fastest_rate_c_per_min"] = e.fastest_rate_c_per_min; break;
      case ConfoundingReason::same_part:
        j["intervals_95"] = {{e.a, {e.interval_a.lower, e.interval_a.upper}}, {e.b, {e.interval_b.lower, e.interval_b.upper}}};
        [[fallthrough]];
      case ConfoundingReason::encompasses: j["pair"] = {e.a, e.b}; break;
      default: break;
    }
    evidence.push_back(j);
  }
  return {{"members", g.members}, {"evidence", evidence}, {"text", confounding_text(g)}};
}

}  // namespace

void check_something_left_to_try(const std::vector<const fit::Term*>& terms, const fit::PreparedData& data) {
  std::size_t available = 0;
  for (const fit::Term* t : fit::term_registry()) available += !t->needs_temp2() || data.has_temp2();
  if (terms.size() >= available)
    throw InputError(fmt::format(
        "model '{}' already contains every term that can be tried on this data{}: there is "
        "nothing left to try (see 'gyrotherm effects'; drop terms with --model to test them)",
        fit::formula_text(terms), data.has_temp2() ? "" : " (grad needs a temp2_c column)"));
}

std::optional<PlanSuggestion> plan_suggestion(const Diagnosis& d, const std::vector<const fit::Term*>& terms,
                                              const fit::PreparedData& data) {
  if (d.candidates.empty() || data.series.temp_c.empty()) return std::nullopt;
  const CandidateReport& front = d.candidates.front();
  if (!front.passed() || front.confounded_with.empty()) return std::nullopt;
  std::vector<std::string> members = {std::string(front.term->name)};
  members.insert(members.end(), front.confounded_with.begin(), front.confounded_with.end());
  PlanSuggestion p;
  p.model = fit::formula_text(terms);
  for (const std::string& name : members) {
    const fit::Term* t = fit::find_term(name);  // registry effects only; nullptr for "1"
    if (t == nullptr || std::find(terms.begin(), terms.end(), t) != terms.end()) continue;
    const auto first = std::find_if(d.first_round.begin(), d.first_round.end(),
                                     [&](const CandidateReport& c) { return c.term == t; });
    const bool known = first != d.first_round.end();
    p.separate.emplace_back(name, known ? first->coefficient : std::nan(""));
    if (t->parameter && known && std::isfinite(first->parameter)) p.param.emplace_back(name, first->parameter);
  }
  if (p.separate.empty()) return std::nullopt;  // one member left: told apart from the model's terms
  const auto [lo, hi] = std::minmax_element(data.series.temp_c.begin(), data.series.temp_c.end());
  p.low_c = kPlanRangeStepC * std::floor(*lo / kPlanRangeStepC);
  p.high_c = std::max(p.low_c + kPlanRangeStepC, kPlanRangeStepC * std::ceil(*hi / kPlanRangeStepC));
  for (const ConfoundingGroup& g : d.confounded)
    if (g.holds(std::string(front.term->name)))
      for (const ConfoundingEvidence& e : g.evidence) p.range_too_narrow |= e.reason == ConfoundingReason::narrow_range;
  return p;
}

std::string plan_command_text(const PlanSuggestion& p) {
  const auto& [model, separate, param, low_c, high_c, range_too_narrow] = p;
  // Sizes for all or for none: plan takes either form.
  const bool sized = std::all_of(separate.begin(), separate.end(), [](const auto& m) { return std::isfinite(m.second); });
  std::vector<std::string> list, params;
  for (const auto& [name, size] : separate) list.push_back(sized ? fmt::format("{}={:.3g}", name, size) : name);
  for (const auto& [name, value] : param)
    params.push_back(fmt::format(" --param {}", shell_word(fmt::format("{}={:.6g}", name, value))));
  return fmt::format("gyrotherm plan --model {} --separate {}{}{}", single_quoted(model),
                     shell_word(fmt::format("{}", fmt::join(list, ","))), fmt::join(params, ""),
                     range_too_narrow ? std::string() : fmt::format(" --range {:g},{:g}", low_c, high_c));
}

DiagnoseReport diagnose_record(const fit::PreparedData& data, const fit::ColumnMap& columns,
                               const std::vector<const fit::Term*>& base_terms,
                               const std::vector<const fit::Term*>& terms, const fit::EngineInfo& engine,
                               const fit::EngineSettings& settings, const DiagnosisOptions& options) {
  DiagnoseReport r;
  r.base_terms = base_terms;
  r.terms = terms;
  r.engine = engine.name;
  r.record = data.file;
  r.start_time_s = data.series.start_time_s;
  r.options = options;
  r.options.stage = nullptr;
  fit::check_columns(terms, data, columns);
  check_something_left_to_try(terms, data);
  r.diagnosis = diagnose(data, terms, engine, settings, options);
  // Step 5: with --add, the model without the added terms is the "before".
  if (terms.size() > base_terms.size()) r.before = diagnose(data, base_terms, engine, settings, options);
  // plan designs a gyro's test only, so far: for another sensor none is suggested.
  if (data.units.kind().is_gyro) r.plan = plan_suggestion(r.diagnosis, terms, data);
  return r;
}

std::string next_command(const DiagnoseReport& report) {
  if (report.diagnosis.suggested.empty()) return "";
  return next_step_text(report.record, report.diagnosis.suggested, report.channel, report.style, report.data_options);
}

nlohmann::ordered_json diagnosis_json(const DiagnoseReport& report) {
  const Diagnosis& d = report.diagnosis;
  const std::optional<Diagnosis>& before = report.before;
  const double start = report.start_time_s;
  nlohmann::ordered_json j;
  if (!d.sensor->is_gyro) {  // (a gyro's is as it was; the *_dph fields are in this unit)
    j["sensor"] = d.sensor->name;
    j["unit"] = d.sensor->unit;
  }
  j["model"] = fit::formula_text(report.terms);
  j["engine"] = report.engine;
  j["instability_dph"] = d.fit.instability_after_dph;
  j["instability_before_dph"] = d.fit.instability_before_dph;
  j["noise_floor_dph"] = d.noise_floor_dph;
  if (d.fit.noise) j["noise_model"] = fit::noise_model_json(d.fit.noise->model);
  if (d.noise) j["noise_model_found"] = fit::noise_model_json(d.noise->model);
  j["noise_floor"] = {{"method", d.floor.method == FloorMethod::hadamard ? "hadamard" : "within-window scatter"},
                      {"description", floor_description(d.floor)},
                      {"hadamard_triples", d.floor.triples},
                      {"hadamard_dph", d.floor.hadamard_dph},
                      {"within_window_dph", d.floor.within_dph}};
  j["ratio_to_floor"] = d.excess_ratio();
  nlohmann::ordered_json segments = nlohmann::ordered_json::array();
  for (std::size_t i : d.worst_segments()) segments.push_back(segment_json(d.segments[i], start));
  j["segments"] = segments;
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (const auto& b : d.bands) bands.push_back(segment_json(b, start));
  j["bands"] = bands;
  nlohmann::ordered_json effects = nlohmann::ordered_json::array();
  for (const CandidateReport& c : d.candidates) {
    nlohmann::ordered_json e = {{"term", c.term->name},
                                {"meaning", c.term->meaning},
                                {"coefficient", c.coefficient},
                                {"coefficient_interval_95", {c.coefficient_interval.lower, c.coefficient_interval.upper}},
                                {"instability_after_dph", c.instability_after_dph},
                                {"reduction_pct", c.reduction_pct},
                                // Alone only: a member of a confounded group is not
                                // significant by itself; the group is.
                                {"significant", c.passed() && c.confounded_with.empty()},
                                {"group_significant", c.passed() && !c.confounded_with.empty()},
                                {"p_value", c.p_value}};
    // The likelihood test's other numbers, then the check and the group.
    const std::pair<const char*, double> test[] = {
        {"level", c.level}, {"p_bootstrap", c.p_bootstrap}, {"effective_tests", c.tests},
        {"likelihood_share", c.likelihood_share}};
    for (const auto& [name, value] : test) e[name] = value;
    e["round"] = c.round;
    e["cv_gain_pct"] = std::isfinite(c.cv_gain_pct) ? nlohmann::ordered_json(c.cv_gain_pct) : nlohmann::ordered_json(nullptr);
    e["confounded_with"] = c.confounded_with;
    if (c.term->parameter) e[c.term->parameter->name] = c.parameter;
    effects.push_back(e);
  }
  j["missing_effects"] = effects;
  j["skipped"] = skipped_texts(d.skipped);
  j["columns_tried"] = d.columns_tried;
  j["significance"] = significance_text(report.options);
  j["warnings"] = fit::fit_warnings(d.fit);
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const StepEvent& e : d.events)
    events.push_back({{"kind", "step"},
                      {"time_s", e.time_s},
                      {"log_time_s", e.log_time_s},
                      {"size_dph", e.size_dph},
                      {"size_interval_dph", {e.size_interval_dph.lower, e.size_interval_dph.upper}},
                      {"significant", e.significant},
                      {"p_value", e.p_value}});
  j["events"] = events;
  j["remaining"] = d.remaining ? remaining_text(*d.remaining) : std::string();
  nlohmann::ordered_json confounded = nlohmann::ordered_json::array(), texts = nlohmann::ordered_json::array(),
                         groups = nlohmann::ordered_json::array();
  for (const ConfoundingGroup& g : d.confounded) {
    confounded.push_back(g.members);
    texts.push_back(confounding_text(g));
    groups.push_back(group_json(g));
  }
  j["confounded"] = confounded;
  j["confounding"] = texts;
  j["confounded_groups"] = groups;
  j["verdict"] = verdict_text(d);
  nlohmann::ordered_json verdict = {{"kind", verdict_name(d.verdict.kind)}, {"limited", d.verdict.limited}};
  std::vector<std::string> found;
  for (std::size_t i : d.verdict.found) found.push_back(std::string(d.candidates[i].term->name));
  if (d.verdict.kind == VerdictKind::found) {
    verdict["terms"] = found;
    verdict["removed_pct"] = d.verdict.removed_pct;
  }
  if (d.verdict.kind == VerdictKind::group) {
    verdict["group"] = d.confounded[d.verdict.group].members;
    verdict["removed_pct"] = d.verdict.removed_pct;
  }
  j["verdict_data"] = verdict;
  j["next_command"] =
      next_step_text(report.record, d.suggested, report.channel, CallStyle::command_line, report.data_options);
  if (d.suggested.empty()) j["next_command"] = "";
  nlohmann::ordered_json given = nlohmann::ordered_json::object();
  for (const GivenOption& o : report.data_options)
    if (report.channel.empty() || o.keyword != "gyro_col") given[o.keyword] = o.value;
  j["next"] = d.suggested.empty() ? nlohmann::ordered_json(nullptr)
                                   : nlohmann::ordered_json{{"model", fit::formula_text(d.suggested)},
                                                            {"channel", report.channel},
                                                            {"options", given}};
  j["plan_command"] = report.plan ? plan_command_text(*report.plan) : std::string();
  if (report.plan) {
    nlohmann::ordered_json separate = nlohmann::ordered_json::object(), param = nlohmann::ordered_json::object();
    for (const auto& [name, size] : report.plan->separate)
      separate[name] = std::isfinite(size) ? nlohmann::ordered_json(size) : nlohmann::ordered_json(nullptr);
    for (const auto& [name, value] : report.plan->param) param[name] = value;
    j["plan"] = {{"model", report.plan->model},
                 {"separate", separate},
                 {"param", param},
                 {"range_c", {report.plan->low_c, report.plan->high_c}},
                 {"range_separates", !report.plan->range_too_narrow}};
  }
  if (before) {
    j["before_after"] = {{"model_before", fit::formula_text(report.base_terms)},
                         {"instability_before_dph", before->fit.instability_after_dph},
                         {"instability_after_dph", d.fit.instability_after_dph}};
  }
  return j;
}

}  // namespace gyrotherm::studies
