// Step 3 of diagnose() (studies/diagnose/diagnosis.h): which effect is
// missing. Candidates scored by block cross-validation with a sign-flip test,
// ranked greedily.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "fit/engines/ols.h"
#include "fit/model/formula.h"
#include "sim/util/input_error.h"
#include "sim/util/random.h"
#include "studies/diagnose/confounding.h"
#include "studies/diagnose/diagnosis_steps.h"

namespace gyrotherm::studies::diagnosis_steps {
namespace {

constexpr int kFoldGrid = 41;  // parameter values each fold chooses among, log-spaced over the bounds (fit_parameters' own grid)
// A rival explains at least this share of what the best does: a near-equal
// explanation, worth fitting together with it (at half, a step was grouped
// with turn-on transients that explained much less: results/diagnosis_false_alarms.md
// lost 13 of 100 steps found).
constexpr double kRivalShare = 0.8;

// Cross-validated SSE per block: each block predicted by the model fitted
// without it, by the fitter's own least squares (fit/model/linear_problem.h,
// nearly collinear terms kept: only the predictions count); +∞ where the rows
// left cannot be fitted.
std::vector<double> block_sse(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                              const std::vector<std::size_t>& block, std::size_t blocks,
                              const std::vector<std::string>& names, std::size_t only = SIZE_MAX) {
  std::vector<double> sse(blocks, 0.0);
  for (std::size_t k = 0; k < blocks; ++k) {
    if (only != SIZE_MAX && k != only) continue;
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

// As block_sse, for a model whose last term has a fitted parameter: in every
// fold the parameter is chosen again on the training rows alone (the grid
// `designs`, one per value, by the training rows' least-squares SSE from
// normal equations on scaled columns, y centred),
// so a filter's time constant tuned on all the data does not see the block it
// predicts. The chosen design then predicts the block as block_sse does.
std::vector<double> block_sse_refit(const std::vector<Eigen::MatrixXd>& designs, const Eigen::VectorXd& y,
                                    const std::vector<std::size_t>& block, std::size_t blocks,
                                    const std::vector<std::string>& names) {
  const Eigen::Index l = y.size();
  const Eigen::VectorXd yc = y.array() - y.mean();  // the intercept is in every design: SSEs unchanged
  std::vector<Eigen::MatrixXd> scaled;  // [1, X] with unit-norm columns
  std::vector<Eigen::MatrixXd> gram_total;
  std::vector<Eigen::VectorXd> xty_total;
  for (const Eigen::MatrixXd& x : designs) {
    Eigen::MatrixXd xs(l, x.cols() + 1);
    xs.col(0).setOnes();
    xs.rightCols(x.cols()) = x;
    for (Eigen::Index j = 0; j < xs.cols(); ++j)
      if (const double norm = xs.col(j).norm(); norm > 0.0) xs.col(j) /= norm;
    gram_total.push_back(xs.transpose() * xs);
    xty_total.push_back(xs.transpose() * yc);
    scaled.push_back(std::move(xs));
  }
  const double yy_total = yc.squaredNorm();
  std::vector<double> sse(blocks, 0.0);
  for (std::size_t k = 0; k < blocks; ++k) {
    std::vector<Eigen::Index> held;
    for (std::size_t p = 0; p < block.size(); ++p)
      if (block[p] == k) held.push_back(static_cast<Eigen::Index>(p));
    std::size_t chosen = 0;
    double best = std::numeric_limits<double>::infinity();
    const Eigen::VectorXd yk = yc(held);
    for (std::size_t g = 0; g < designs.size(); ++g) {
      const Eigen::MatrixXd xk = scaled[g](held, Eigen::all);
      const Eigen::MatrixXd gram = gram_total[g] - xk.transpose() * xk;
      const Eigen::VectorXd xty = xty_total[g] - xk.transpose() * yk;
      const Eigen::VectorXd b = gram.ldlt().solve(xty);
      const double train = yy_total - yk.squaredNorm() - 2.0 * b.dot(xty) + b.dot(gram * b);
      if (std::isfinite(train) && train < best) {
        best = train;
        chosen = g;
      }
    }
    // The chosen design's prediction of block k, by block_sse's own path.
    const std::vector<double> one = block_sse(designs[chosen], y, block, blocks, names, k);
    sse[k] = one[k];
  }
  return sse;
}

// One-sided sign-flip randomisation test of Σ d_k > 0.
double sign_flip_p(const std::vector<double>& d, int draws, std::uint64_t seed) {
  double observed = 0.0;
  for (double v : d) observed += v;
  Rng rng = make_rng(seed, streams::diagnosis_sign_flips);
  int at_least = 0;
  const std::size_t n = d.size();
  for (int i = 0; i < draws; ++i) {
    // 64 signs from each 64-bit draw; Σ ±d_k = 2 Σ_{sign +} d_k − Σ d_k.
    double plus = 0.0;
    for (std::size_t k = 0; k < n; k += 64) {
      const std::uint64_t bits = rng();
      const std::size_t end = std::min(n, k + 64);
      for (std::size_t j = k; j < end; ++j) plus += static_cast<double>((bits >> (j - k)) & 1u) * d[j];
    }
    at_least += 2.0 * plus - observed >= observed - 1e-15 * std::abs(observed);
  }
  return (at_least + 1.0) / (draws + 1.0);
}

std::size_t parameter_count(const fit::Term* t) { return t->parameter ? 1 : 0; }

// The round's best is significant; before it joins, the rivals that remove at
// least kRivalShare as much are fitted together with it (separate()). Returns the
// candidate that joins: the best, a rival that encompasses it (and passed the
// test itself), or, of a group the record cannot tell apart, the member with
// the fewest fitted parameters (marked group_significant).
std::size_t resolve_rivals(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& current,
                           std::vector<CandidateReport>& round, std::size_t best) {
  std::vector<std::pair<std::size_t, Separation>> inseparable;
  std::size_t encompassing = best;
  for (std::size_t i = 0; i < round.size(); ++i) {
    if (i == best || !(round[i].reduction_pct >= kRivalShare * round[best].reduction_pct)) continue;
    Separation s;
    try {
      s = separate(data, current, round[best].term, round[i].term);
    } catch (const InputError&) {
      continue;  // collinear with the model: the pairwise rule speaks for it
    }
    if (s.a_adds) continue;  // the best adds to it: the greedy order stands
    if (s.b_adds && round[i].significant) {
      if (encompassing == best || round[i].reduction_pct > round[encompassing].reduction_pct) encompassing = i;
      continue;
    }
    if (s.note.empty())
      s.note = fmt::format("{} encompasses {} on this record, but did not pass the test alone", round[i].term->name,
                           round[best].term->name);
    inseparable.emplace_back(i, std::move(s));
  }
  // A rival that encompasses the best and passed the test joins instead;
  // the best's other rivals are judged again in the next round.
  if (encompassing != best) return encompassing;
  std::size_t leader = best;
  for (const auto& [i, s] : inseparable) {
    d.inseparable.push_back({std::string(round[best].term->name), std::string(round[i].term->name), s.note});
    round[best].group_significant = round[i].group_significant = true;
    if (leader == best && parameter_count(round[i].term) < parameter_count(round[best].term)) leader = i;
  }
  return leader;
}

}  // namespace

std::vector<StepCandidate> rank_candidates(Diagnosis& d, const fit::PreparedData& data,
                                           const std::vector<const fit::Term*>& terms,
                                           const DiagnosisOptions& options) {
  const fit::AveragedSeries& s = data.series;
  const std::size_t l = s.size();
  // Candidates, ranked greedily: score every unused term against the
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
  d.columns_tried = std::move(candidates.columns);
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
  std::vector<std::pair<std::string, std::string>> failed;  // term, why; each term's first
  for (int round_number = 1; !untried.empty(); ++round_number) {
    if (options.stage)
      options.stage(fmt::format("scoring {} candidates by block cross-validation, round {}", untried.size(),
                                round_number));
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
        const fit::Coefficients fitted = problem.physical(fit::least_squares_optimum(problem));
        const double sigma = problem.sigma_two_pass(fitted);
        std::vector<double> sse;
        if (term->parameter) {
          // The grid of the parameter's values (log-spaced over its bounds),
          // each a design; not the full-record optimum: it has seen every block.
          std::vector<Eigen::MatrixXd> designs;
          const double lo = std::log(term->parameter->lower), hi = std::log(term->parameter->upper);
          for (int g = 0; g < kFoldGrid; ++g) {
            std::vector<double> p = params;
            p.back() = std::exp(lo + (hi - lo) * g / (kFoldGrid - 1));
            designs.push_back(fit::design_matrix(data.derived, with, p));
          }
          sse = block_sse_refit(designs, y, block, blocks, fit::term_names(with));
        } else {
          sse = block_sse(xw, y, block, blocks, fit::term_names(with));
        }
        std::vector<double> gains(blocks);
        double cv = 0.0;
        for (std::size_t k = 0; k < blocks; ++k) {
          gains[k] = base_sse[k] - sse[k];
          cv += sse[k];
        }
        CandidateReport c;
        c.term = term;
        c.parameter = params.back();
        c.coefficient = fitted.b.back();  // the term is the last of `with`
        c.instability_after_dph = sigma;
        c.reduction_pct = 100.0 * (current_sigma2 - sigma * sigma) / excess;
        c.cv_gain_pct = 100.0 * (base_cv - cv) / base_cv;
        c.p_value = sign_flip_p(gains, options.permutations, options.seed);
        c.significant = c.p_value < corrected && c.cv_gain_pct > 0.0 &&
                        c.reduction_pct >= options.min_reduction_pct;
        round.push_back(c);
        round_params.push_back(params);
      } catch (const InputError& e) {
        if (std::none_of(failed.begin(), failed.end(), [&](const auto& f) { return f.first == term->name; }))
          failed.emplace_back(std::string(term->name), e.what());
      }
    }
    if (round_number == 1) d.first_round = round;  // before resolve_rivals marks groups
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
    const std::size_t leader = resolve_rivals(d, data, current, round, best);
    d.candidates.push_back(round[leader]);
    current.push_back(round[leader].term);
    current_params = round_params[leader];
    current_sigma2 = round[leader].instability_after_dph * round[leader].instability_after_dph;
    untried.erase(std::find(untried.begin(), untried.end(), round[leader].term));
  }
  // Candidates that could not be fitted (collinear with the model, say),
  // each named once, with the first round's reason (later rounds' differ only
  // in their condition numbers).
  for (const auto& [name, why] : failed) d.skipped.push_back(name + " (" + why + ")");
  return steps;
}

}  // namespace gyrotherm::studies::diagnosis_steps
