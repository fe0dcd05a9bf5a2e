#include "studies/diagnose/diagnosis.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fit/engines/ols.h"
#include "fit/model/formula.h"
#include "fit/model/noise_whitening.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"
#include "studies/diagnose/confounding.h"
#include "studies/diagnose/diagnosis_steps.h"
#include "sim/util/numbers.h"

namespace gyrotherm::studies {
namespace {

// 1. Compare: the model as given, its residual, and the noise floor.
void compare(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
             const fit::EngineInfo& engine, const fit::EngineSettings& settings) {
  d.fit = fit::fit_model(data, terms, engine, settings);
  d.floor = estimate_noise_floor(data.series, data.derivative_span_s);
  d.noise_floor_dph = d.floor.dph;
}

// 4. What the record cannot tell apart: the model's terms and every candidate
// tried, at their fitted parameters, and the pairs the ranking fitted together.
void name_confounded(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                     const std::vector<ConfoundingEvidence>& inseparable) {
  std::vector<const fit::Term*> all = terms;
  std::vector<double> params = d.fit.parameters;
  for (const CandidateReport& c : d.candidates) {
    // A step that did not pass is the step family's best position of the
    // last round, often beside one that joined: no rival explanation.
    if (fit::is_step_term(c.term) && !c.significant) continue;
    all.push_back(c.term);
    params.push_back(c.parameter);
  }
  d.confounded = find_confounding(data.derived, all, params);
  for (const ConfoundingEvidence& e : inseparable) add_group(d.confounded, e);
  for (CandidateReport& c : d.candidates)
    for (const ConfoundingGroup& g : d.confounded)
      if (g.holds(std::string(c.term->name))) {
        c.confounded_with = g.members;
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

// The bias steps: those that joined the model, and the step family's best of
// the last round where its own p-value is below α (located, but not
// significant against the family), each sized by GLS with the final model
// under the final noise.
void size_steps(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                const DiagnosisOptions& options) {
  std::vector<const fit::Term*> final_terms = terms;
  for (const CandidateReport& c : d.candidates)
    if (c.significant) final_terms.push_back(c.term);
  const std::vector<double> params = fit::fit_parameters(data.derived, data.series.gyro_dph, final_terms);
  const Eigen::VectorXd y =
      Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(), static_cast<Eigen::Index>(data.series.size()));
  std::vector<fit::NoiseWhitener> whiteners;  // the point model first, then those the record supports alike
  for (const fit::NoiseModel& m : fit::plausible_models(d.noise->model, d.noise->grid)) {
    try {
      whiteners.emplace_back(m, d.noise->grid);
    } catch (const FitError&) {
    }
  }
  if (whiteners.empty()) return;
  for (const CandidateReport& c : d.candidates) {
    if (!fit::is_step_term(c.term) || !(c.significant || c.p_value < options.alpha)) continue;
    std::vector<const fit::Term*> with = final_terms;
    std::vector<double> p = params;
    if (std::find(with.begin(), with.end(), c.term) == with.end()) {
      with.push_back(c.term);
      p.push_back(std::nan(""));
    }
    const auto k = static_cast<Eigen::Index>(std::find(with.begin(), with.end(), c.term) - with.begin()) + 1;
    try {
      const Eigen::MatrixXd x = fit::design_matrix(data.derived, with, p);
      const fit::GlsFit f = fit::gls(whiteners.front(), x, y);
      StepEvent e;
      e.time_s = c.term->step_time_s;
      e.log_time_s = e.time_s + data.series.start_time_s;
      e.size_dph = f.beta[k];
      const double half =
          kZ95 * std::sqrt(std::max({0.0, f.covariance(k, k), fit::widest_variance(whiteners, x, k)}));
      e.size_interval_dph = {e.size_dph - half, e.size_dph + half};
      e.p_value = c.p_value;
      e.significant = c.significant && c.confounded_with.empty();
      d.events.push_back(e);
    } catch (const FitError&) {
    }
  }
  std::sort(d.events.begin(), d.events.end(), [](const StepEvent& a, const StepEvent& b) { return a.time_s < b.time_s; });
}

// What is left: the model with every significant candidate, against the floor.
void find_what_remains(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms) {
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
    const std::vector<double> params = fit::fit_parameters(data.derived, data.series.gyro_dph, final_terms);
    const fit::LinearProblem problem(
        fit::design_matrix(data.derived, final_terms, params),
        Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(), static_cast<Eigen::Index>(data.series.size())),
        fit::term_names(final_terms), fit::Collinear::keep);
    const fit::Coefficients c = problem.physical(fit::least_squares_optimum(problem));
    const double after = problem.sigma_two_pass(c);
    if (after <= kStructureRemains * d.noise_floor_dph) return;
    const Eigen::VectorXd r = problem.residuals(c);
    const std::vector<SegmentReport> rows = segment_rms(d, std::vector<double>(r.data(), r.data() + r.size()));
    Remaining left;
    left.with_candidates = final_terms.size() > terms.size();
    left.ratio_to_floor = after / d.noise_floor_dph;
    left.worst = *std::max_element(rows.begin(), rows.end(), [](const SegmentReport& a, const SegmentReport& b) {
      return a.ratio_to_floor < b.ratio_to_floor;
    });
    d.remaining = left;
  } catch (const FitError&) {
  }
}

// 5. The verdict, and the model it suggests (the significant candidates that stand alone).
void decide(Diagnosis& d, const std::vector<const fit::Term*>& terms) {
  Verdict& v = d.verdict;
  if (d.candidates.empty()) {
    v.kind = VerdictKind::nothing_to_try;
    return;
  }
  const CandidateReport& first = d.candidates.front();
  if (first.passed() && !first.confounded_with.empty()) {
    v.kind = VerdictKind::group;
    v.removed_pct = first.reduction_pct;
    for (std::size_t g = 0; g < d.confounded.size(); ++g)
      if (d.confounded[g].holds(std::string(first.term->name))) v.group = g;
    return;
  }
  if (!first.significant) {
    v.kind = VerdictKind::none;
    return;
  }
  v.kind = VerdictKind::found;
  d.suggested = terms;
  for (std::size_t i = 0; i < d.candidates.size(); ++i) {
    const CandidateReport& c = d.candidates[i];
    if (!c.significant || !c.confounded_with.empty()) break;
    v.found.push_back(i);
    v.removed_pct += c.reduction_pct;
    d.suggested.push_back(c.term);
  }
}

}  // namespace

Diagnosis diagnose(const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                   const fit::EngineInfo& engine, const fit::EngineSettings& settings,
                   const DiagnosisOptions& options) {
  if (data.series.size() < kMinBlocks)
    throw InputError(fmt::format(
        "{}: only {}: diagnose needs at least {} (a shorter --avg gives more windows, "
        "if the record's runs allow it)",
        data.file, counted(data.series.size(), "window"), kMinBlocks));
  Diagnosis d;
  d.sensor = &data.units.kind();
  const auto stage = [&](const std::string& what) {
    if (options.stage) options.stage(what);
  };
  stage("fitting the model and its noise");
  compare(d, data, terms, engine, settings);
  diagnosis_steps::locate_failures(d, data);
  stage("testing the candidates and the steps");
  std::vector<ConfoundingEvidence> inseparable;
  diagnosis_steps::rank_candidates(d, data, terms, options, inseparable);
  stage("what the record cannot tell apart, and what remains");
  name_confounded(d, data, terms, inseparable);
  size_steps(d, data, terms, options);
  find_what_remains(d, data, terms);
  decide(d, terms);
  return d;
}

}  // namespace gyrotherm::studies
