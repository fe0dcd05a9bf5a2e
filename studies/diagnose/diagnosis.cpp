#include "studies/diagnose/diagnosis.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/data/median.h"
#include "fit/model/formula.h"
#include "studies/diagnose/candidates.h"
#include "studies/diagnose/confounding.h"
#include "fit/engines/ols.h"
#include "sim/util/input_error.h"
#include "sim/util/random.h"

namespace gyrotherm::studies {
namespace {

constexpr double kMedianChi2One = 0.454936;

// Cross-validated SSE per block: each block predicted by the model fitted
// without it, by the fitter's own least squares (fit/model/linear_problem.h,
// nearly collinear terms kept: only the predictions count); +∞ where the rows
// left cannot be fitted.
std::vector<double> block_sse(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                              const std::vector<std::size_t>& block, std::size_t blocks,
                              const std::vector<std::string>& names) {
  std::vector<double> sse(blocks, 0.0);
  for (std::size_t k = 0; k < blocks; ++k) {
    std::vector<Eigen::Index> train;
    for (std::size_t p = 0; p < block.size(); ++p)
      if (block[p] != k) train.push_back(static_cast<Eigen::Index>(p));
    fit::Coefficients c;
    try {
      const fit::LinearProblem problem(x(train, Eigen::all), y(train), names, fit::Collinear::keep);
      c = problem.physical(fit::least_squares_optimum(problem));
    } catch (const InputError&) {
      sse[k] = std::numeric_limits<double>::infinity();
      continue;
    }
    for (std::size_t p = 0; p < block.size(); ++p) {
      if (block[p] != k) continue;
      const auto pp = static_cast<Eigen::Index>(p);
      double r = y[pp] - c.intercept;
      for (Eigen::Index j = 0; j < x.cols(); ++j) r -= c.b[static_cast<std::size_t>(j)] * x(pp, j);
      sse[k] += r * r;
    }
  }
  return sse;
}

// One-sided sign-flip randomisation test of Σ d_k > 0.
double sign_flip_p(const std::vector<double>& d, int draws, std::uint64_t seed) {
  double observed = 0.0;
  for (double v : d) observed += v;
  Rng rng = make_rng(seed, streams::diagnosis_sign_flips);
  int at_least = 0;
  for (int i = 0; i < draws; ++i) {
    double s = 0.0;
    for (double v : d) s += (rng() & 1u) ? v : -v;
    at_least += s >= observed - 1e-15 * std::abs(observed);
  }
  return (at_least + 1.0) / (draws + 1.0);
}


}  // namespace

namespace {

// The squared second differences of equally spaced window means (within
// 10 %) of one gap-free run, or across gaps no farther apart than span_s.
std::vector<double> hadamard_squares(const fit::AveragedSeries& s, double span_s) {
  std::vector<double> h2;
  for (std::size_t p = 1; p + 1 < s.size(); ++p) {
    const double before = s.time_s[p] - s.time_s[p - 1], after = s.time_s[p + 1] - s.time_s[p];
    const bool one_run = s.run[p - 1] == s.run[p] && s.run[p + 1] == s.run[p];
    if (!one_run && std::max(before, after) > span_s) continue;
    if (std::abs(before - after) > 0.1 * std::max(before, after)) continue;
    const double h = s.gyro_dph[p + 1] - 2.0 * s.gyro_dph[p] + s.gyro_dph[p - 1];
    h2.push_back(h * h);
  }
  return h2;
}

// The root mean square of the windows' standard errors (header, step 1).
double within_window_floor(const fit::AveragedSeries& s) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < s.size() && p < s.gyro_sd_dph.size(); ++p) {
    if (s.samples[p] < 2) continue;
    const double rho = std::clamp(s.gyro_lag1[p], -0.5, 0.95);
    sum += s.gyro_sd_dph[p] * s.gyro_sd_dph[p] * (1.0 + rho) /
           ((1.0 - rho) * static_cast<double>(s.samples[p]));
    ++n;
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

}  // namespace

double robust_noise_floor(const fit::AveragedSeries& s) {
  const std::vector<double> h2 = hadamard_squares(s, std::numeric_limits<double>::infinity());
  if (h2.size() < 5)
    throw InputError(fmt::format("only {} usable windows: too few to estimate the noise floor",
                                 s.size()));
  return std::sqrt(fit::median_of(h2) / (6.0 * kMedianChi2One));
}

NoiseFloor estimate_noise_floor(const fit::AveragedSeries& s, double span_s) {
  NoiseFloor f;
  const std::vector<double> h2 = hadamard_squares(s, span_s);
  f.triples = h2.size();
  if (!h2.empty()) f.hadamard_dph = std::sqrt(fit::median_of(h2) / (6.0 * kMedianChi2One));
  f.within_dph = within_window_floor(s);
  if (f.triples >= kMinHadamardTriples) {
    f.method = "hadamard";
    f.dph = f.hadamard_dph;
  } else if (f.within_dph > 0.0) {
    f.method = "within-window scatter";
    f.dph = f.within_dph;
  } else {
    throw InputError(fmt::format(
        "only {} windows ({} equally spaced triples): too few to estimate the noise floor from "
        "the window means, and the windows hold too few samples to estimate it from their scatter",
        s.size(), f.triples));
  }
  return f;
}

std::string NoiseFloor::description() const {
  if (method == "hadamard")
    return fmt::format("robust Hadamard deviation of the window means, {} triples", triples);
  return fmt::format(
      "from the scatter inside the windows (the standard error of a window mean, corrected for "
      "the autocorrelation of its samples): only {} equally spaced triples of windows, fewer than "
      "the {} a Hadamard estimate needs; noise slower than a window is not in it and shows as "
      "excess",
      triples, kMinHadamardTriples);
}

std::vector<std::size_t> Diagnosis::worst_segments() const {
  std::vector<std::size_t> idx(segments.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return segments[a].ratio_to_floor > segments[b].ratio_to_floor;
  });
  return idx;
}

std::vector<SegmentReport> segment_rms(const Diagnosis& d, const std::vector<double>& residual) {
  std::vector<SegmentReport> out = d.segments;
  std::vector<double> ss(out.size(), 0.0);
  for (std::size_t p = 0; p < residual.size(); ++p) ss[d.window_segment[p]] += residual[p] * residual[p];
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].rms_dph = std::sqrt(ss[i] / static_cast<double>(out[i].windows));
    out[i].ratio_to_floor = out[i].rms_dph / d.noise_floor_dph;
  }
  return out;
}

Diagnosis diagnose(const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                   const fit::EngineInfo& engine, const fit::EngineSettings& settings,
                   const DiagnosisOptions& options) {
  Diagnosis d;
  const fit::AveragedSeries& s = data.series;
  const std::size_t l = s.size();
  if (l < kMinBlocks)
    throw InputError(fmt::format(
        "{}: only {} windows: diagnose needs at least {} (a shorter --avg gives more windows, "
        "if the record's runs allow it)",
        data.file, l, kMinBlocks));

  // 1. Compare.
  d.fit = fit::fit_model(data, terms, engine, settings);
  d.floor = estimate_noise_floor(s, data.derivative_span_s);
  d.noise_floor_dph = d.floor.dph;
  const Eigen::MatrixXd x = fit::design_matrix(data.derived, terms, d.fit.parameters);
  d.model_dph = fit::model_values(x, d.fit.coefficients);
  d.residual_dph.resize(l);
  for (std::size_t p = 0; p < l; ++p) d.residual_dph[p] = s.gyro_dph[p] - d.model_dph[p];

  // 2. Segments from the temperature record.
  const std::vector<double>& rate = data.derived.rate_c_per_s;
  double max_rate = 0.0;
  for (double r : rate) max_rate = std::max(max_rate, std::abs(r));
  const double threshold = std::max(2e-4, 0.05 * max_rate);
  std::vector<std::string> kind(l);
  for (std::size_t p = 0; p < l; ++p) {
    if (s.time_s[p] - s.start_time_s < 1800.0)
      kind[p] = "turn-on";
    else if (rate[p] > threshold)
      kind[p] = "heating";
    else if (rate[p] < -threshold)
      kind[p] = "cooling";
    else
      kind[p] = "soak";
  }
  // Runs shorter than 3 windows take the kind of the run before them.
  for (std::size_t p = 0; p < l;) {
    std::size_t q = p;
    while (q < l && kind[q] == kind[p]) ++q;
    if (q - p < 3 && p > 0 && kind[p] != "turn-on")
      for (std::size_t i = p; i < q; ++i) kind[i] = kind[p - 1];
    p = q;
  }
  d.window_segment.resize(l);
  for (std::size_t p = 0; p < l; ++p) {
    // A segment ends where the kind changes or the record stops for longer
    // than the derivatives' span (a bursty logger's bursts stay together).
    const bool new_segment = p == 0 || kind[p] != kind[p - 1] ||
                             (s.run[p] != s.run[p - 1] &&
                              s.time_s[p] - s.time_s[p - 1] > data.derivative_span_s);
    if (new_segment) {
      SegmentReport seg;
      seg.kind = kind[p];
      seg.start_s = s.time_s[p];
      seg.temp_min_c = seg.temp_max_c = s.temp_c[p];
      d.segments.push_back(seg);
    }
    SegmentReport& seg = d.segments.back();
    seg.end_s = s.time_s[p];
    seg.temp_min_c = std::min(seg.temp_min_c, s.temp_c[p]);
    seg.temp_max_c = std::max(seg.temp_max_c, s.temp_c[p]);
    seg.windows += 1;
    d.window_segment[p] = d.segments.size() - 1;
  }
  d.segments = segment_rms(d, d.residual_dph);

  // Temperature bands: four of equal width.
  const auto [tlo, thi] = std::minmax_element(s.temp_c.begin(), s.temp_c.end());
  const double width = std::max((*thi - *tlo) / 4.0, 1e-9);
  d.bands.resize(4);
  std::vector<double> band_ss(4, 0.0);
  for (int b = 0; b < 4; ++b) {
    d.bands[static_cast<std::size_t>(b)].kind = "band";
    d.bands[static_cast<std::size_t>(b)].temp_min_c = *tlo + b * width;
    d.bands[static_cast<std::size_t>(b)].temp_max_c = *tlo + (b + 1) * width;
    d.bands[static_cast<std::size_t>(b)].start_s = std::numeric_limits<double>::infinity();
    d.bands[static_cast<std::size_t>(b)].end_s = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t p = 0; p < l; ++p) {
    const auto b = static_cast<std::size_t>(std::min(3.0, std::floor((s.temp_c[p] - *tlo) / width)));
    d.bands[b].windows += 1;
    band_ss[b] += d.residual_dph[p] * d.residual_dph[p];
    d.bands[b].start_s = std::min(d.bands[b].start_s, s.time_s[p]);
    d.bands[b].end_s = std::max(d.bands[b].end_s, s.time_s[p]);
  }
  for (std::size_t b = 0; b < 4; ++b) {
    if (d.bands[b].windows == 0) continue;
    d.bands[b].rms_dph = std::sqrt(band_ss[b] / static_cast<double>(d.bands[b].windows));
    d.bands[b].ratio_to_floor = d.bands[b].rms_dph / d.noise_floor_dph;
  }
  std::erase_if(d.bands, [](const SegmentReport& b) { return b.windows == 0; });

  // 3. Candidates, ranked greedily: score every unused term against the
  // current model; if the best is significant it joins the model and the rest
  // are scored again against the larger model (so a second effect is judged
  // on what the first leaves), until the best is not significant.
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(s.gyro_dph.data(), static_cast<Eigen::Index>(l));
  // Blocks of block_windows, smaller on a short record so that there are at
  // least kMinBlocks of them (a sign-flip test on fewer cannot reach p < α).
  const std::size_t block_windows =
      std::clamp<std::size_t>(l / kMinBlocks, 1, options.block_windows);
  const std::size_t blocks = std::max<std::size_t>(2, l / block_windows);
  std::vector<std::size_t> block(l);
  for (std::size_t p = 0; p < l; ++p) block[p] = std::min(blocks - 1, p * blocks / l);
  const double after2 = d.fit.instability_after_dph * d.fit.instability_after_dph;
  const double floor2 = d.noise_floor_dph * d.noise_floor_dph;
  // The excess over the floor; when the model is at the floor already, the
  // share is of the whole residual variance.
  const double excess = after2 > floor2 ? after2 - floor2 : after2;

  CandidateSet candidates =
      candidate_set(data, terms, d.fit.parameters, options.candidates, options.excluded_columns, options.seed);
  std::vector<const fit::Term*> untried = std::move(candidates.terms);
  d.skipped = std::move(candidates.skipped);
  const std::vector<StepCandidate> steps = std::move(candidates.steps);
  // What the record can support: the smallest p of a sign-flip test on B
  // blocks is 2^−B, so at most ⌊α·2^B⌋ candidates can pass Bonferroni; each
  // needs 3 residual degrees of freedom left with it and its parameter. The
  // simplest candidates (no parameter) are tried first, in registry order.
  const std::size_t supported = std::min<std::size_t>(
      untried.size(), static_cast<std::size_t>(std::floor(
                          options.alpha * std::pow(2.0, static_cast<double>(std::min<std::size_t>(blocks, 30))))));
  std::stable_partition(untried.begin(), untried.end(), [](const fit::Term* t) { return !t->parameter; });
  std::vector<const fit::Term*> tried;
  for (std::size_t i = 0; i < untried.size(); ++i) {
    const std::size_t parameters = terms.size() + 2 + (untried[i]->parameter ? 1 : 0);
    const bool no_dof = l < parameters + 3;
    if (i < supported && !no_dof) {
      tried.push_back(untried[i]);
      continue;
    }
    d.limited = true;
    d.skipped.push_back(fmt::format(
        "{} (not tried: {} windows {})", untried[i]->name, l,
        no_dof ? std::string("leave too few degrees of freedom for it")
               : fmt::format("in {} blocks support at most {} candidate test{}", blocks, supported,
                             supported == 1 ? "" : "s")));
  }
  untried = std::move(tried);
  const double corrected =
      options.alpha / static_cast<double>(std::max<std::size_t>(1, untried.size()));
  std::vector<const fit::Term*> current = terms;
  std::vector<double> current_params = d.fit.parameters;
  double current_sigma2 = after2;
  std::vector<std::string> failed;
  while (!untried.empty()) {
    const Eigen::MatrixXd xc = fit::design_matrix(data.derived, current, current_params);
    const std::vector<double> base_sse = block_sse(xc, y, block, blocks, fit::term_names(current));
    double base_cv = 0.0;
    for (double v : base_sse) base_cv += v;
    std::vector<CandidateReport> round;
    std::vector<std::vector<double>> round_params;
    for (const fit::Term* term : untried) {
      std::vector<const fit::Term*> with = current;
      with.push_back(term);
      try {
        const std::vector<double> params = fit::fit_parameters(data.derived, s.gyro_dph, with);
        const Eigen::MatrixXd xw = fit::design_matrix(data.derived, with, params);
        const fit::LinearProblem problem(xw, y, fit::term_names(with));
        const double sigma = problem.sigma_two_pass(problem.physical(fit::least_squares_optimum(problem)));
        const std::vector<double> sse = block_sse(xw, y, block, blocks, fit::term_names(with));
        std::vector<double> gains(blocks);
        double cv = 0.0;
        for (std::size_t k = 0; k < blocks; ++k) {
          gains[k] = base_sse[k] - sse[k];
          cv += sse[k];
        }
        CandidateReport c;
        c.term = term;
        c.parameter = params.back();
        c.instability_after_dph = sigma;
        c.reduction_pct = 100.0 * (current_sigma2 - sigma * sigma) / excess;
        c.cv_gain_pct = 100.0 * (base_cv - cv) / base_cv;
        c.p_value = sign_flip_p(gains, options.permutations, options.seed);
        c.significant = c.p_value < corrected && c.cv_gain_pct > 0.0 &&
                        c.reduction_pct >= options.min_reduction_pct;
        round.push_back(c);
        round_params.push_back(params);
      } catch (const InputError& e) {
        failed.push_back(std::string(term->name) + " (" + e.what() + ")");
      }
    }
    if (round.empty()) break;
    std::size_t best = 0;
    for (std::size_t i = 1; i < round.size(); ++i) {
      const bool better = round[i].significant != round[best].significant
                              ? round[i].significant
                              : round[i].reduction_pct > round[best].reduction_pct;
      if (better) best = i;
    }
    if (!round[best].significant) {
      std::stable_sort(round.begin(), round.end(), [](const CandidateReport& a, const CandidateReport& b) {
        return a.reduction_pct > b.reduction_pct;
      });
      for (const CandidateReport& c : round) d.candidates.push_back(c);
      break;
    }
    d.candidates.push_back(round[best]);
    current.push_back(round[best].term);
    current_params = round_params[best];
    current_sigma2 = round[best].instability_after_dph * round[best].instability_after_dph;
    untried.erase(std::find(untried.begin(), untried.end(), round[best].term));
  }
  // Candidates that could not be fitted (collinear with the model, say),
  // each named once.
  std::sort(failed.begin(), failed.end());
  failed.erase(std::unique(failed.begin(), failed.end()), failed.end());
  for (const std::string& f : failed) d.skipped.push_back(f);

  // What the record cannot tell apart: the model's terms and every candidate
  // tried, at their fitted parameters.
  {
    std::vector<const fit::Term*> all = terms;
    std::vector<double> params = d.fit.parameters;
    for (const CandidateReport& c : d.candidates) {
      all.push_back(c.term);
      params.push_back(c.parameter);
    }
    const Confounding confounding = find_confounding(data.derived, all, params);
    d.confounded = confounding.groups;
    d.confounding_notes = confounding.notes;
    for (CandidateReport& c : d.candidates)
      if (const auto* group = confounding.group_of(std::string(c.term->name)); group != nullptr) {
        c.confounded_with = *group;
        std::erase(c.confounded_with, std::string(c.term->name));
      }
  }

  // The steps found, each sized with the model (ols) and judged by the
  // candidates' test.
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

  // What is left: the model with every significant candidate, against the floor.
  {
    std::vector<const fit::Term*> final_terms = terms;
    for (const CandidateReport& c : d.candidates) {
      if (!c.significant || !c.confounded_with.empty()) break;
      final_terms.push_back(c.term);
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
            "worst in the {} segment at {:.2f}–{:.2f} h ({:.1f} to {:.1f} °C), {:.2f} times the floor",
            final_terms.size() > terms.size() ? "the model with the significant candidates" : "the model",
            f.instability_after_dph / d.noise_floor_dph, worst->kind,
            (worst->start_s - s.start_time_s) / 3600.0, (worst->end_s - s.start_time_s) / 3600.0,
            worst->temp_min_c, worst->temp_max_c, worst->ratio_to_floor);
      }
    } catch (const InputError&) {
    }
  }

  // The verdict.
  const double ratio = d.excess_ratio();
  const std::string limited =
      d.limited ? " (this record supported fewer tests than there are candidates; see 'not tried')"
                : "";
  if (d.candidates.empty()) {
    d.verdict = fmt::format(
        "The model is {:.2f} times the noise floor and there is nothing left to try: every "
        "available term is already in it.",
        ratio);
  } else if (d.candidates.front().significant && !d.candidates.front().confounded_with.empty()) {
    // Significant, but not alone: say which effects it cannot be told from.
    const CandidateReport& c = d.candidates.front();
    std::string others;
    for (const std::string& o : c.confounded_with)
      others += (others.empty() ? "" : ", ") + (o == "1" ? std::string("a constant offset") : o);
    d.verdict = fmt::format(
        "The model is {:.2f} times the noise floor; adding {} ({}) would remove {:.0f} % of the "
        "excess, but on this record it cannot be told apart from {}, so the data do not say which "
        "effect it is: {}",
        ratio, c.term->name, c.term->meaning, c.reduction_pct, others,
        d.confounding_notes.empty() ? std::string() : d.confounding_notes.front());
  } else if (d.candidates.front().significant) {
    std::vector<const fit::Term*> suggested = terms;
    std::string found;
    double removed = 0.0;
    for (const CandidateReport& c : d.candidates) {
      if (!c.significant || !c.confounded_with.empty()) break;
      suggested.push_back(c.term);
      found += fmt::format("{}{} ({})", found.empty() ? "" : " and then ", c.term->name, c.term->meaning);
      removed += c.reduction_pct;
    }
    d.suggested_model = fit::formula_text(suggested);
    d.verdict = fmt::format(
        "The model is {:.2f} times the noise floor; adding {} removes {:.0f} % of the excess, "
        "significant under block cross-validation.",
        ratio, found, std::min(removed, 100.0));
  } else {
    d.verdict = fmt::format(
        "The model is {:.2f} times the noise floor; no missing effect is significant under "
        "block cross-validation{}, so no term should be added.",
        ratio, limited);
  }
  if (!d.remaining.empty()) d.verdict += " Still, " + d.remaining + ".";
  return d;
}

}  // namespace gyrotherm::studies
