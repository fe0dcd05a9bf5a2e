// Step 3 of diagnose() (studies/diagnose/diagnosis.h): which effect is
// missing. Candidates scored by block cross-validation with a sign-flip test,
// ranked greedily.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/engines/ols.h"
#include "fit/model/formula.h"
#include "sim/util/input_error.h"
#include "sim/util/random.h"
#include "studies/diagnose/diagnosis_steps.h"

namespace gyrotherm::studies::diagnosis_steps {
namespace {

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
  return steps;
}

}  // namespace gyrotherm::studies::diagnosis_steps
