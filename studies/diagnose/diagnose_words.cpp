#include "studies/diagnose/diagnose_words.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <string_view>

#include "fit/model/formula.h"
#include "sim/util/format.h"

namespace gyrotherm::studies {
namespace {

std::string direction_text(Direction d) {
  switch (d) {
    case Direction::cools: return "it only cools";
    case Direction::heats: return "it only heats";
    case Direction::both: return "temperature follows time";
  }
  return "";
}

// Why, in the record's own terms, and the test that would separate them.
std::pair<std::string, std::string> why_and_test(const ConfoundingEvidence& e) {
  switch (e.reason) {
    case ConfoundingReason::temperature_follows_time:
      return {fmt::format("temperature and time move together on this record (r = {:.3f}: {})", e.correlation,
                          direction_text(e.direction)),
              "a test with both a heating and a cooling leg, or a soak, would separate them"};
    case ConfoundingReason::constant_rate:
      return {fmt::format("the temperature changes at an almost constant rate ({} °C/h), so a rate effect acts as "
                          "a constant offset",
                          human(e.rate_c_per_h)),
              "a test with varied rates (ramps and soaks) would separate them"};
    case ConfoundingReason::settling_curve:
      return {"the temperature settles along one curve, its rate moving with its distance from the end value, so "
              "temperature and rate effects look alike",
              "a test with ramps at several rates and soaks would separate them"};
    case ConfoundingReason::narrow_range:
      return {fmt::format("over the record's {:.1f}..{:.1f} °C their regressors are nearly proportional", e.temp_min_c,
                          e.temp_max_c),
              "a wider temperature range would separate them"};
    case ConfoundingReason::lag_follows_temperature:
      return {fmt::format("a lagged temperature differs from the temperature by about the lag times dT/dt, and the "
                          "fastest change on this record is {:.2g} °C/min", e.fastest_rate_c_per_min),
              "faster ramps (or a step of the chamber's temperature) would separate them"};
    case ConfoundingReason::proportional:
      return {"their regressors are nearly proportional over this record",
              "a test with another profile would separate them"};
    case ConfoundingReason::same_part:
      return {fmt::format("fitted together, neither {} nor {} adds significantly to what the other explains (95 % "
                          "intervals under the record's identified noise: {} [{:.3g}, {:.3g}], {} [{:.3g}, {:.3g}])",
                          e.a, e.b, e.a, e.interval_a.lower, e.interval_a.upper, e.b, e.interval_b.lower,
                          e.interval_b.upper),
              "a record on which they differ (other temperature rates or gradients) would separate them"};
    case ConfoundingReason::encompasses:
      return {fmt::format("{} encompasses {} on this record, but did not pass the test alone", e.a, e.b),
              "a record on which they differ (other temperature rates or gradients) would separate them"};
  }
  return {};
}

}  // namespace

std::string hours_text(double seconds) { return fmt::format("{:.2f} h", seconds / 3600.0); }

std::string p_text(double p, double level) {
  std::string text = fmt::format("{:.2g}", p);
  for (int digits = 3; digits <= 6 && p != level && text == fmt::format("{:.{}g}", level, digits - 1); ++digits)
    text = fmt::format("{:.{}g}", p, digits);
  return text;
}

std::string floor_description(const NoiseFloor& f) {
  if (f.method == FloorMethod::hadamard)
    return fmt::format("robust Hadamard deviation of the window means, {}", counted(f.triples, "triple"));
  return fmt::format(
      "from the scatter inside the windows (the standard error of a window mean, corrected for "
      "the autocorrelation of its samples): only {} equally spaced triples of windows, fewer than "
      "the {} a Hadamard estimate needs; noise slower than a window is not in it and shows as "
      "excess",
      f.triples, kMinHadamardTriples);
}

std::string excess_share_text(double pct) {
  if (pct < kBelowFloorPct) return fmt::format("{:.0f} % of the excess", pct);
  return fmt::format("all of the excess ({:.0f} %, below the estimated floor)", pct);
}

std::string share_cell(double pct) { return pct < kBelowFloorPct ? fmt::format("{:.0f} %", pct) : excess_share_text(pct); }

std::string member_list(const std::vector<std::string>& members, const char* last) {
  std::string list;
  for (std::size_t k = 0; k < members.size(); ++k)
    list += (k == 0 ? "" : k + 1 == members.size() ? last : ", ") +
            (members[k] == "1" ? std::string("a constant offset") : members[k]);
  return list;
}

std::string confounding_text(const ConfoundingGroup& g) {
  std::vector<std::string> whys, tests;
  for (const ConfoundingEvidence& e : g.evidence) {
    auto [why, test] = why_and_test(e);
    if (std::find(whys.begin(), whys.end(), why) == whys.end()) whys.push_back(why);
    if (std::find(tests.begin(), tests.end(), test) == tests.end()) tests.push_back(test);
  }
  return fmt::format("{} cannot be told apart on this record: {}; {}.", member_list(g.members),
                     fmt::join(whys, "; "), fmt::join(tests, "; "));
}

std::string remaining_text(const Remaining& r) {
  return fmt::format(
      "structure remains that no candidate explains: {} is still {:.2f} times the floor, worst in the {} segment at "
      "{}–{} ({} °C), {:.2f} times the floor",
      r.with_candidates ? "the model with the significant candidates (or their group)" : "the model", r.ratio_to_floor,
      to_string(r.worst.kind), hours_text(r.worst.start_s), hours_text(r.worst.end_s),
      range_text(r.worst.temp_min_c, r.worst.temp_max_c, 1, " to "), r.worst.ratio_to_floor);
}

std::vector<std::string> skipped_texts(const std::vector<Skipped>& skipped) {
  std::vector<std::string> out;
  std::map<fit::ColumnRole, std::vector<std::string>> by_role;
  for (const Skipped& s : skipped) {
    switch (s.reason) {
      case SkipReason::needs_temp2: out.push_back(s.name + " (needs temp2_c)"); break;
      case SkipReason::unwritable_name:
        out.push_back(fmt::format("column '{}' (its name cannot be written in a model: use letters, digits, '_' and '.')",
                                  s.name));
        break;
      case SkipReason::column_role: by_role[s.role].push_back(s.name); break;
      case SkipReason::too_few_windows:
        out.push_back(fmt::format("{} (not tried: {} leave too few degrees of freedom for it)", s.name,
                                  counted(s.windows, "window")));
        break;
      case SkipReason::not_fitted: out.push_back(fmt::format("{} ({})", s.name, s.error)); break;
    }
  }
  for (const auto& [role, names] : by_role) {
    const bool many = names.size() > 1;
    const std::string what = fit::to_string(role);  // the role's words, as fit/data/column_role.h has them
    out.push_back(fmt::format("column{} {} ({}{}, not a cause of the bias; name one in --candidates +NAME to try it)",
                              many ? "s" : "", fmt::join(names, ", "), what,
                              many && role != fit::ColumnRole::constant && role != fit::ColumnRole::derived ? "s" : ""));
  }
  return out;
}

std::string verdict_text(const Diagnosis& d) {
  const Verdict& v = d.verdict;
  std::string verdict;
  switch (v.kind) {
    case VerdictKind::nothing_to_try: verdict = "nothing left to try: every available term is already in the model"; break;
    case VerdictKind::none:
      // Absence of evidence, said as such: a test that finds nothing on a
      // record with few levels or one direction of change has little power.
      verdict = fmt::format("no missing effect is significant under the record's identified noise{}: the record "
                            "gives no evidence for another term, which is no proof that none is missing (a record "
                            "over more temperatures, both ways, tests harder)",
                            v.limited ? " (this record supported fewer tests than there are candidates; see 'not tried')"
                                      : "");
      break;
    case VerdictKind::group: {
      const CandidateReport& c = d.candidates.front();
      // A term of the model is not missing: it is named apart, as what the missing one cannot be told from.
      std::vector<std::string> members = {std::string(c.term->name)}, in_model;
      for (const std::string& m : c.confounded_with) {
        const bool modelled = std::any_of(d.fit.terms.begin(), d.fit.terms.end(),
                                          [&](const fit::Term* t) { return t->name == m; });
        (modelled ? in_model : members).push_back(m);
      }
      verdict = fmt::format("{} is missing, and this record cannot tell {}: {} ({}) removes {} (p = {})",
                            members.size() == 1 ? members.front() : "one of " + member_list(members, " or "),
                            members.size() == 1 ? fmt::format("it from {}, in the model", member_list(in_model))
                            : in_model.empty()  ? std::string("which")
                                                : fmt::format("which, nor them from {}, in the model", member_list(in_model)),
                            c.term->name, c.term->meaning, excess_share_text(c.reduction_pct),
                            p_text(c.p_value, c.level));
      break;
    }
    case VerdictKind::found: {
      std::vector<std::string> parts;
      for (std::size_t i : v.found) {
        const CandidateReport& c = d.candidates[i];
        parts.push_back(fmt::format("{} ({}): {:.3g} {} (95 % [{:.3g}, {:.3g}]), removes {} (p = {})",
                                    c.term->name, c.term->meaning, c.coefficient, c.term->coefficient_unit(d.sensor->unit),
                                    c.coefficient_interval.lower, c.coefficient_interval.upper,
                                    excess_share_text(c.reduction_pct), p_text(c.p_value, c.level)));
      }
      verdict = fmt::format("add {}", fmt::join(parts, "; then "));
      break;
    }
  }
  if (d.remaining) verdict += "; " + remaining_text(*d.remaining);
  return verdict;
}

namespace {

// A value as a Python literal: a number or flag bare, text quoted.
std::string python_literal(const GivenOption& o) {
  if (o.kind == OptionKind::flag) return o.value == "true" ? "True" : "False";
  if (o.kind == OptionKind::number || o.kind == OptionKind::integer) return o.value;
  std::string quoted = "'";
  for (char c : o.value) quoted += c == '\'' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string next_step_text(const std::string& record, const std::vector<const fit::Term*>& model,
                           const std::string& channel, CallStyle style, const std::vector<GivenOption>& data_options) {
  std::string rest;
  for (const GivenOption& o : data_options) {
    if (!channel.empty() && o.keyword == "gyro_col") continue;  // the channel's own, below
    if (style == CallStyle::python)
      rest += fmt::format(", {}={}", o.keyword, python_literal(o));
    else
      rest += o.kind == OptionKind::flag ? (o.value == "true" ? " " + o.flag : std::string())
                                         : fmt::format(" {} {}", o.flag, shell_word(o.value));
  }
  if (style == CallStyle::python)
    return fmt::format("gyrotherm.diagnose(data, model=\"{}\"{}{})", fit::formula_text(model),
                       channel.empty() ? "" : fmt::format(", gyro_col='{}'", channel), rest);
  return fmt::format("gyrotherm diagnose {} --model \"{}\"{}{}", shell_word(record), fit::formula_text(model),
                     channel.empty() ? "" : " --gyro-col " + shell_word(channel), rest);
}

std::string significance_text(const DiagnosisOptions& o) {
  return fmt::format(
      "likelihood under the record's identified noise (REML, identified again with each round's leading candidate "
      "as a fixed effect): the share of the whitened residual each candidate removes at its best parameter or step "
      "position, p from a parametric bootstrap of {} draws (Sidak over the grid's effective number of tests), the "
      "largest over the noise models the record supports alike; weighted step-down over the candidates at {:g} "
      "(each registry term and the step family weigh 1, the log's columns together 1; Sidak over the family's "
      "effective number of tests from the same draws), and at least {:g} % of the excess removed",
      o.draws, o.alpha, o.min_reduction_pct);
}

}  // namespace gyrotherm::studies
