#include "studies/diagnose/diagnosis.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fit/model/formula.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"
#include "studies/diagnose/confounding.h"
#include "studies/diagnose/diagnosis_steps.h"

namespace gyrotherm::studies {
namespace {

// 1. Compare: the model as given, its residual, and the noise floor.
void compare(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
             const fit::EngineInfo& engine, const fit::EngineSettings& settings) {
  const fit::AveragedSeries& s = data.series;
  d.fit = fit::fit_model(data, terms, engine, settings);
  d.floor = estimate_noise_floor(s, data.derivative_span_s);
  d.noise_floor_dph = d.floor.dph;
  const Eigen::MatrixXd x = fit::design_matrix(data.derived, terms, d.fit.parameters);
  d.model_dph = fit::model_values(x, d.fit.coefficients);
  d.residual_dph.resize(s.size());
  for (std::size_t p = 0; p < s.size(); ++p) d.residual_dph[p] = s.gyro_dph[p] - d.model_dph[p];
}

// 4. What the record cannot tell apart: the model's terms and every candidate
// tried, at their fitted parameters.
void name_confounded(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms) {
  std::vector<const fit::Term*> all = terms;
  std::vector<double> params = d.fit.parameters;
  for (const CandidateReport& c : d.candidates) {
    all.push_back(c.term);
    params.push_back(c.parameter);
  }
  Confounding confounding = find_confounding(data.derived, all, params);
  for (const auto& [a, b, note] : d.inseparable) add_group(confounding, a, b, note);
  d.confounded = confounding.groups;
  d.confounding_notes = confounding.notes;
  for (CandidateReport& c : d.candidates)
    if (const auto* group = confounding.group_of(std::string(c.term->name)); group != nullptr) {
      c.confounded_with = *group;
      std::erase(c.confounded_with, std::string(c.term->name));
    }
  // A group passed the test when any member did (alone, or standing for it).
  for (CandidateReport& c : d.candidates) {
    if (c.confounded_with.empty()) continue;
    for (const CandidateReport& o : d.candidates)
      if (std::find(c.confounded_with.begin(), c.confounded_with.end(), std::string(o.term->name)) !=
          c.confounded_with.end())
        c.group_significant = c.group_significant || o.significant || o.group_significant;
    c.group_significant = c.group_significant || c.significant;
  }
}

// The bias steps found, each sized with the model (ols) and judged by the
// candidates' test.
void size_steps(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                const std::vector<StepCandidate>& steps) {
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                                             static_cast<Eigen::Index>(data.series.size()));
  for (const StepCandidate& found : steps) {
    const fit::Term* step = fit::step_term(found.time_s);
    StepEvent e;
    e.time_s = found.time_s;
    e.p_value = found.p_value;
    try {
      std::vector<const fit::Term*> with = terms;
      if (std::find(with.begin(), with.end(), step) == with.end()) with.push_back(step);
      const fit::ModelFit f = fit::fit_model(data, with, fit::find_engine("ols"), {});
      e.size_dph = f.coefficients.b.back();
      // The wider of ols's interval and ±1.96 placebo spreads (steps.h).
      const double placebo = placebo_step_sd(fit::design_matrix(data.derived, with, f.parameters), y, found.index);
      const fit::Interval ols = f.engine.intervals.back();
      const double half = std::max(0.5 * (ols.upper - ols.lower), 1.96 * placebo);
      e.size_interval_dph = {e.size_dph - half, e.size_dph + half};
    } catch (const InputError&) {
      continue;
    }
    for (const CandidateReport& c : d.candidates)
      if (c.term == step) e.significant = c.significant && c.confounded_with.empty();
    d.events.push_back(e);
  }
}

// What is left: the model with every significant candidate, against the floor.
void find_what_remains(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms) {
  const fit::AveragedSeries& s = data.series;
  const std::size_t l = s.size();
  std::vector<const fit::Term*> final_terms = terms;
  // A significant group (terms this record cannot tell apart) explains what
  // it explains whichever member stands for it: its first member joins,
  // then the selection stops, as it does.
  for (const CandidateReport& c : d.candidates) {
    if (!c.passed()) break;
    final_terms.push_back(c.term);
    if (!c.confounded_with.empty()) break;
  }
  try {
    const fit::ModelFit f = fit::fit_model(data, final_terms, fit::find_engine("ols"), {});
    if (f.instability_after_dph > kStructureRemains * d.noise_floor_dph) {
      Diagnosis at_end = d;
      at_end.fit = f;
      const Eigen::MatrixXd xf = fit::design_matrix(data.derived, final_terms, f.parameters);
      const std::vector<double> mf = fit::model_values(xf, f.coefficients);
      std::vector<double> rf(l);
      for (std::size_t p = 0; p < l; ++p) rf[p] = s.gyro_dph[p] - mf[p];
      const std::vector<SegmentReport> rows = segment_rms(at_end, rf);
      const auto worst = std::max_element(rows.begin(), rows.end(), [](const SegmentReport& a, const SegmentReport& b) {
        return a.ratio_to_floor < b.ratio_to_floor;
      });
      d.remaining = fmt::format(
          "structure remains that no candidate explains: {} is still {:.2f} times the floor, "
          "worst in the {} segment at {:.2f}–{:.2f} h ({} °C), {:.2f} times the floor",
          final_terms.size() > terms.size() ? "the model with the significant candidates (or their group)" : "the model",
          f.instability_after_dph / d.noise_floor_dph, worst->kind,
          (worst->start_s - s.start_time_s) / 3600.0, (worst->end_s - s.start_time_s) / 3600.0,
          range_text(worst->temp_min_c, worst->temp_max_c, 1, " to "), worst->ratio_to_floor);
    }
  } catch (const InputError&) {
  }
}

// 5. The verdict, in words; *suggested is the model with the significant
// candidates that stand alone, or "".
std::string verdict_of(const Diagnosis& d, const std::vector<const fit::Term*>& terms, std::string* suggested) {
  const double ratio = d.excess_ratio();
  std::string verdict;
  if (d.candidates.empty()) {
    verdict = fmt::format(
        "The model is {:.2f} times the noise floor and there is nothing left to try: every "
        "available term is already in it.",
        ratio);
  } else if (d.candidates.front().passed() && !d.candidates.front().confounded_with.empty()) {
    // Significant, but not alone: say which effects it cannot be told from,
    // and why (the note of its own group).
    const CandidateReport& c = d.candidates.front();
    std::string others, why;
    for (const std::string& o : c.confounded_with)
      others += (others.empty() ? "" : ", ") + (o == "1" ? std::string("a constant offset") : o);
    for (std::size_t g = 0; g < d.confounded.size() && g < d.confounding_notes.size(); ++g)
      if (std::find(d.confounded[g].begin(), d.confounded[g].end(), std::string(c.term->name)) != d.confounded[g].end())
        why = d.confounding_notes[g];
    verdict = fmt::format(
        "The model is {:.2f} times the noise floor; adding {} ({}) would remove {}, but on this "
        "record it cannot be told apart from {}, so the data do not say which effect it is: {}",
        ratio, c.term->name, c.term->meaning, excess_share_text(c.reduction_pct), others, why);
  } else if (d.candidates.front().significant) {
    std::vector<const fit::Term*> with = terms;
    std::string found;
    double removed = 0.0;
    for (const CandidateReport& c : d.candidates) {
      if (!c.significant || !c.confounded_with.empty()) break;
      with.push_back(c.term);
      found += fmt::format("{}{} ({})", found.empty() ? "" : " and then ", c.term->name, c.term->meaning);
      removed += c.reduction_pct;
    }
    *suggested = fit::formula_text(with);
    verdict = fmt::format(
        "The model is {:.2f} times the noise floor; adding {} removes {}, "
        "significant under block cross-validation.",
        ratio, found, excess_share_text(removed));
  } else {
    verdict = fmt::format(
        "The model is {:.2f} times the noise floor; no missing effect is significant under "
        "block cross-validation{}, so no term should be added.",
        ratio, d.limited ? " (this record supported fewer tests than there are candidates; see 'not tried')" : "");
  }
  if (!d.remaining.empty()) verdict += " Still, " + d.remaining + ".";
  return verdict;
}

}  // namespace

std::string excess_share_text(double pct) {
  if (pct < kBelowFloorPct) return fmt::format("{:.0f} % of the excess", pct);
  return fmt::format("all of the excess ({:.0f} %, below the estimated floor)", pct);
}

Diagnosis diagnose(const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                   const fit::EngineInfo& engine, const fit::EngineSettings& settings,
                   const DiagnosisOptions& options) {
  if (data.series.size() < kMinBlocks)
    throw InputError(fmt::format(
        "{}: only {}: diagnose needs at least {} (a shorter --avg gives more windows, "
        "if the record's runs allow it)",
        data.file, counted(data.series.size(), "window"), kMinBlocks));
  Diagnosis d;
  const auto stage = [&](const std::string& what) {
    if (options.stage) options.stage(what);
  };
  stage("fitting the model and its noise");
  compare(d, data, terms, engine, settings);
  diagnosis_steps::locate_failures(d, data);
  stage("searching for steps and scoring the candidates");
  const std::vector<StepCandidate> steps = diagnosis_steps::rank_candidates(d, data, terms, options);
  stage("what the record cannot tell apart, and what remains");
  name_confounded(d, data, terms);
  size_steps(d, data, terms, steps);
  find_what_remains(d, data, terms);
  d.verdict = verdict_of(d, terms, &d.suggested_model);
  return d;
}

}  // namespace gyrotherm::studies
