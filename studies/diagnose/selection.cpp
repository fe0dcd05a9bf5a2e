// Step 3 of diagnose() (studies/diagnose/diagnosis.h): which effect is
// missing. Candidates tested by likelihood under the record's identified
// noise (likelihood_test.h), the family-wise error held step-down (Holm)
// with the family's effective number of tests,
// ranked greedily.
#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>

#include "fit/engines/ols.h"
#include "fit/model/formula.h"
#include "fit/model/noise_whitening.h"
#include "sim/util/input_error.h"
#include "studies/diagnose/diagnosis_steps.h"
#include "studies/diagnose/likelihood_test.h"

namespace gyrotherm::studies::diagnosis_steps {
namespace {

constexpr int kParameterGrid = 25;                // a parameter's values, log-spaced over its bounds
constexpr std::size_t kMostStepPositions = 256;   // positions of the step family's grid
constexpr std::size_t kStepMargin = 4;            // windows a step leaves on either side
constexpr std::size_t kMostSteps = 3;             // steps that may join the model
// Block means of the noise identification: finer than the fit's 64, so a
// slow component is bounded more tightly (fit/model/noise_model.h).
constexpr std::size_t kDiagnoseBlocks = 128;
// A rival explains at least this share of what the best does: a near-equal
// explanation, worth fitting together with it.
constexpr double kRivalShare = 0.8;

// One candidate's grid: its columns, one per value of its parameter (or per
// step position), and its weight in the family-wise correction.
struct Grid {
  const fit::Term* term = nullptr;  // nullptr: the step family
  double weight = 1.0;
  std::vector<double> values;       // θ of each column (NaN: none), or the step's time since the start
  Eigen::MatrixXd columns;
};

Grid term_grid(const fit::DerivedSeries& derived, const fit::Term* term) {
  Grid g;
  g.term = term;
  if (!term->parameter) {
    g.values = {std::nan("")};
    g.columns = fit::design_matrix(derived, {term}, g.values);
    return g;
  }
  const double lo = std::log(term->parameter->lower), hi = std::log(term->parameter->upper);
  g.columns.resize(static_cast<Eigen::Index>(derived.size()), kParameterGrid);
  for (int k = 0; k < kParameterGrid; ++k) {
    g.values.push_back(std::exp(lo + (hi - lo) * k / (kParameterGrid - 1)));
    g.columns.col(k) = fit::design_matrix(derived, {term}, {g.values.back()}).col(0);
  }
  return g;
}

// A step between window k − 1 and k at every k with kStepMargin windows a
// side (every one, or evenly spread up to kMostStepPositions); its time is
// half-way between the two windows' centres, in whole seconds where that
// stays between them.
Grid step_grid(const fit::AveragedSeries& s) {
  Grid g;
  const std::size_t l = s.size();
  if (l < 2 * kStepMargin + 1) return g;
  const std::size_t first = kStepMargin, last = l - kStepMargin, span = last - first + 1;
  const std::size_t count = std::min(span, kMostStepPositions);
  g.columns = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(l), static_cast<Eigen::Index>(count));
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t k = first + (count > 1 ? i * (span - 1) / (count - 1) : 0);
    const double before = s.time_s[k - 1] - s.start_time_s, after = s.time_s[k] - s.start_time_s;
    double t = std::round(0.5 * (before + after));
    if (!(t > before && t < after)) t = 0.5 * (before + after);
    g.values.push_back(t);
    g.columns.col(static_cast<Eigen::Index>(i)).tail(static_cast<Eigen::Index>(l - k)).setOnes();
  }
  return g;
}

// The noise of y around [1, x] by REML, or white noise of the residual's
// variance where the record is too short to identify more (then the test
// is the classic F test, exact for white noise).
fit::NoiseModel noise_of(const fit::WindowGrid& grid, const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  try {
    return fit::identify_noise(grid, x, y, kDiagnoseBlocks);
  } catch (const FitError&) {
  }
  Eigen::MatrixXd a(x.rows(), x.cols() + 1);
  a << Eigen::VectorXd::Ones(x.rows()), x;
  const Eigen::VectorXd r = y - a * a.colPivHouseholderQr().solve(y);
  fit::NoiseModel white;
  const double dof = std::max(1.0, static_cast<double>(y.size() - a.cols()));
  white.amplitude[fit::kWhite] = std::max(r.squaredNorm() / dof, 1e-300) * grid.window_s;
  white.present[fit::kWhite] = white.identified[fit::kWhite] = true;
  return white;
}

Eigen::MatrixXd with_column(const Eigen::MatrixXd& x, const Eigen::VectorXd& c) {
  Eigen::MatrixXd out(x.rows(), x.cols() + 1);
  out << x, c;
  return out;
}

// Block cross-validated SSE of least squares on [1, x]: each block of
// `block` windows predicted by the fit on the others (normal equations on
// unit-norm columns, the block's rows taken out of the totals); +∞ where the
// rows left cannot be fitted.
double cv_sse(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, std::size_t block) {
  const Eigen::Index l = y.size();
  Eigen::MatrixXd a(l, x.cols() + 1);
  a << Eigen::VectorXd::Ones(l), x;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    if (const double n = a.col(j).norm(); n > 0.0) a.col(j) /= n;
  const Eigen::MatrixXd gram = a.transpose() * a;
  const Eigen::VectorXd aty = a.transpose() * y;
  double sse = 0.0;
  for (Eigen::Index start = 0; start < l; start += static_cast<Eigen::Index>(block)) {
    const Eigen::Index rows = std::min<Eigen::Index>(static_cast<Eigen::Index>(block), l - start);
    const auto ak = a.middleRows(start, rows);
    const auto yk = y.segment(start, rows);
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(gram - ak.transpose() * ak);
    if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
    const Eigen::VectorXd b = ldlt.solve(aty - ak.transpose() * yk);
    sse += (yk - ak * b).squaredNorm();
  }
  return std::isfinite(sse) ? sse : std::numeric_limits<double>::infinity();
}

// The 95 % interval of a GLS coefficient with ν residual degrees of freedom.
fit::Interval interval_of(double value, double variance, double dof) {
  const boost::math::students_t t(std::max(1.0, dof));
  const double half = boost::math::quantile(boost::math::complement(t, 0.025)) * std::sqrt(std::max(0.0, variance));
  return {value - half, value + half};
}

// Everything a round knows: the model as it stands and its noise.
struct Round {
  const fit::PreparedData& data;
  const fit::WindowGrid& grid;
  const Eigen::VectorXd& y;
  Eigen::MatrixXd x;  // the current model's regressors
  double sigma2 = 0, excess = 0, base_cv = 0;
};

// Every candidate scored under one noise model; `family_tests` gets the
// family's effective number of tests (likelihood_test.h).
std::vector<CandidateScore> score_all(const fit::NoiseWhitener& whitener, const Round& r,
                                      const std::vector<Grid>& grids, const std::vector<std::size_t>& which,
                                      int draws, std::uint64_t seed, double* family_tests = nullptr,
                                      const Eigen::VectorXd& ar = {}) {
  LikelihoodTest test(whitener, r.x, r.y);
  for (std::size_t j : which) test.add(grids[j].columns, grids[j].weight);
  test.calibrate(draws, seed, ar);
  if (family_tests) *family_tests = test.family_tests();
  std::vector<CandidateScore> out;
  for (std::size_t i = 0; i < which.size(); ++i) out.push_back(test.score(i));
  return out;
}

// The short-lag autoregression of what the model and the round's leader
// leave, whitened (residual_autoregression, likelihood_test.h), up to the
// windows of one of the noise identification's blocks: the correlation the
// block means could not show. Empty where there is none to fit.
Eigen::VectorXd leftover_autoregression(const fit::NoiseWhitener& whitener, const Round& r,
                                        const Eigen::VectorXd& leader, std::size_t blocks) {
  if (blocks == 0) return {};
  const int most = static_cast<int>(std::min<std::size_t>(20, (r.y.size() + blocks - 1) / blocks));
  try {
    return residual_autoregression(fit::gls(whitener, leader.size() > 0 ? with_column(r.x, leader) : r.x, r.y)
                                       .whitened_residual, most);
  } catch (const FitError&) {
    return {};
  }
}

// A candidate's report at its best grid value under the round's noise.
// A parameter's value between the grid's neighbours of the best: the one
// whose column removes the most of the whitened residual (Brent's method on
// ln θ, boost::math::tools::brent_find_minima).
double refined_parameter(const Round& r, const fit::NoiseWhitener& whitener, const Grid& g, std::size_t best) {
  const std::size_t lo = best > 0 ? best - 1 : best, hi = std::min(best + 1, g.values.size() - 1);
  if (lo == hi) return g.values[best];
  Eigen::MatrixXd model(r.x.rows(), r.x.cols() + 1);
  model << Eigen::VectorXd::Ones(r.x.rows()), r.x;
  const Eigen::MatrixXd xw = whitener.whiten(model);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(xw);
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(xw.rows(), xw.cols());
  Eigen::VectorXd e = whitener.whiten(r.y);
  e -= q * (q.transpose() * e);
  const auto loss = [&](double log_theta) {
    Eigen::VectorXd c = whitener.whiten(Eigen::VectorXd(
        fit::design_matrix(r.data.derived, {g.term}, {std::exp(log_theta)}).col(0)));
    c -= q * (q.transpose() * c);
    const double n2 = c.squaredNorm();
    return n2 > 0.0 ? -std::pow(c.dot(e), 2) / n2 : 0.0;
  };
  const auto [x, f] = boost::math::tools::brent_find_minima(loss, std::log(g.values[lo]), std::log(g.values[hi]), 30);
  return f < loss(std::log(g.values[best])) ? std::exp(x) : g.values[best];
}

CandidateReport report_of(const Round& r, const fit::NoiseWhitener& whitener,
                          const std::vector<fit::NoiseWhitener>& plausible, const Grid& g, const CandidateScore& s,
                          double level, std::size_t block, const DiagnosisOptions& options) {
  CandidateReport c;
  c.term = g.term != nullptr ? g.term : fit::step_term(g.values[s.best]);
  Eigen::VectorXd column = g.columns.col(static_cast<Eigen::Index>(s.best));
  if (g.term != nullptr && g.term->parameter) {
    c.parameter = refined_parameter(r, whitener, g, s.best);
    column = fit::design_matrix(r.data.derived, {g.term}, {c.parameter}).col(0);
  }
  const Eigen::MatrixXd xw = with_column(r.x, column);
  const fit::GlsFit f = fit::gls(whitener, xw, r.y);
  const auto last = f.beta.size() - 1;
  const double dof = static_cast<double>(r.y.size() - f.beta.size());
  c.coefficient = f.beta[last];
  c.coefficient_interval =
      interval_of(c.coefficient, std::max(f.covariance(last, last), fit::widest_variance(plausible, xw, last)), dof);
  const fit::LinearProblem problem(xw, r.y, std::vector<std::string>(static_cast<std::size_t>(xw.cols()), "x"),
                                   fit::Collinear::keep);
  c.instability_after_dph = problem.sigma_two_pass(problem.physical(fit::least_squares_optimum(problem)));
  c.reduction_pct = 100.0 * (r.sigma2 - c.instability_after_dph * c.instability_after_dph) / r.excess;
  c.likelihood_share = s.share;
  c.p_value = s.p_value;
  c.p_bootstrap = s.p_bootstrap;
  c.tests = s.tests;
  c.level = level;
  c.cv_gain_pct = 100.0 * (r.base_cv - cv_sse(xw, r.y, block)) / r.base_cv;
  c.significant = s.p_value <= level && c.reduction_pct >= options.min_reduction_pct;
  return c;
}

std::size_t parameter_count(const fit::Term* t) { return t->parameter ? 1 : 0; }

// The round's best is significant; before it joins, the rivals that remove at
// least kRivalShare as much are fitted together with it (GLS under the
// round's noise). Returns the candidate that joins: the best, a rival that
// encompasses it (and passed the test itself), or, of a group the record
// cannot tell apart, the member with the fewest fitted parameters (marked
// group_significant); the pairs it cannot tell apart go to `inseparable`.
std::size_t resolve_rivals(const Round& r, const fit::NoiseWhitener& whitener, const std::vector<Grid>& grids,
                           const std::vector<std::size_t>& which, const std::vector<CandidateScore>& scores,
                           std::vector<CandidateReport>& round, std::size_t best,
                           std::vector<ConfoundingEvidence>& inseparable) {
  std::vector<std::pair<std::size_t, ConfoundingEvidence>> found;
  std::size_t encompassing = best;
  const auto column = [&](std::size_t i) {
    return grids[which[i]].columns.col(static_cast<Eigen::Index>(scores[i].best));
  };
  for (std::size_t i = 0; i < round.size(); ++i) {
    if (i == best || !(round[i].reduction_pct >= kRivalShare * round[best].reduction_pct)) continue;
    fit::GlsFit f;
    try {
      f = fit::gls(whitener, with_column(with_column(r.x, column(best)), column(i)), r.y);
    } catch (const FitError&) {
      continue;  // collinear with the model: the pairwise rule speaks for it
    }
    const auto ia = f.beta.size() - 2, ib = f.beta.size() - 1;
    const double dof = static_cast<double>(r.y.size() - f.beta.size());
    ConfoundingEvidence e;
    e.a = round[best].term->name;
    e.b = round[i].term->name;
    e.interval_a = interval_of(f.beta[ia], f.covariance(ia, ia), dof);
    e.interval_b = interval_of(f.beta[ib], f.covariance(ib, ib), dof);
    const bool a_adds = e.interval_a.lower > 0.0 || e.interval_a.upper < 0.0;
    const bool b_adds = e.interval_b.lower > 0.0 || e.interval_b.upper < 0.0;
    if (a_adds) continue;  // the best adds to it: the greedy order stands
    if (b_adds && round[i].significant) {
      if (encompassing == best || round[i].reduction_pct > round[encompassing].reduction_pct) encompassing = i;
      continue;
    }
    if (b_adds) std::swap(e.a, e.b);  // the rival encompasses the best without passing alone
    e.reason = b_adds ? ConfoundingReason::encompasses : ConfoundingReason::same_part;
    found.emplace_back(i, e);
  }
  // A rival that encompasses the best and passed the test joins instead;
  // the best's other rivals are judged again in the next round.
  if (encompassing != best) return encompassing;
  std::size_t leader = best;
  for (const auto& [i, e] : found) {
    inseparable.push_back(e);
    round[best].group_significant = round[i].group_significant = true;
    if (leader == best && parameter_count(round[i].term) < parameter_count(round[best].term)) leader = i;
  }
  return leader;
}

// The candidates' grids, the weights of the family-wise correction, and what
// cannot be tried.
std::vector<Grid> candidate_grids(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                                  const DiagnosisOptions& options) {
  CandidateSet set = candidate_set(data, terms, options.candidates, options.excluded_columns);
  d.skipped = std::move(set.skipped);
  d.columns_tried = std::move(set.columns);
  const std::size_t l = data.series.size();
  std::vector<Grid> grids;
  std::size_t column_terms = 0;
  for (const fit::Term* t : set.terms) column_terms += fit::is_column_term(t);
  // Registry terms (the simplest first) before the log's columns.
  std::stable_partition(set.terms.begin(), set.terms.end(), [](const fit::Term* t) { return !fit::is_column_term(t); });
  for (const fit::Term* t : set.terms) {
    const std::size_t needed = terms.size() + 2 + parameter_count(t) + 3;
    if (l < needed) {
      d.verdict.limited = true;
      d.skipped.push_back({.name = std::string(t->name), .reason = SkipReason::too_few_windows, .windows = l});
      continue;
    }
    Grid g = term_grid(data.derived, t);
    g.weight = fit::is_column_term(t) ? 1.0 / static_cast<double>(column_terms) : 1.0;
    grids.push_back(std::move(g));
  }
  if (set.steps) {
    Grid g = step_grid(data.series);
    if (g.values.empty()) {
      d.skipped.push_back({.name = "step", .reason = SkipReason::too_few_windows, .windows = l});
    } else {
      grids.push_back(std::move(g));
    }
  }
  return grids;
}

}  // namespace

void rank_candidates(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                     const DiagnosisOptions& options, std::vector<ConfoundingEvidence>& inseparable) {
  const fit::AveragedSeries& s = data.series;
  const std::size_t l = s.size();
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(s.gyro_dph.data(), static_cast<Eigen::Index>(l));
  const fit::WindowGrid grid = fit::window_grid(data);
  const std::size_t block = std::clamp<std::size_t>(l / kMinBlocks, 1, options.block_windows);
  const double floor2 = d.noise_floor_dph * d.noise_floor_dph;
  const double after2 = d.fit.instability_after_dph * d.fit.instability_after_dph;
  // The excess over the floor; when the model is at the floor already, the
  // share is of the whole residual variance.
  const double excess = after2 > floor2 ? after2 - floor2 : after2;

  const std::vector<Grid> grids = candidate_grids(d, data, terms, options);
  std::vector<std::size_t> untried(grids.size());
  for (std::size_t j = 0; j < grids.size(); ++j) untried[j] = j;
  std::vector<const fit::Term*> current = terms;
  std::vector<double> params = d.fit.parameters;
  Round r{data, grid, y, fit::design_matrix(data.derived, current, params), after2, excess, 0.0};
  fit::NoiseModel noise = d.fit.noise ? d.fit.noise->model : noise_of(grid, r.x, y);
  std::size_t steps_joined = 0;
  std::vector<std::pair<std::string, std::string>> failed;  // term, why; each term's first
  for (int round_number = 1; !untried.empty(); ++round_number) {
    if (options.stage)
      options.stage(fmt::format("testing {} candidates under the record's noise, round {}", untried.size(), round_number));
    r.base_cv = cv_sse(r.x, y, block);
    // 1. The leading candidate: the one that removes the most of the
    // residual by least squares.
    const auto seed = options.seed + static_cast<std::uint64_t>(round_number);
    const fit::NoiseModel without = noise;  // the model as it stands: the final noise when nothing joins
    Eigen::VectorXd leading;                // the leading candidate's column
    {
      fit::NoiseModel white;
      white.amplitude[fit::kWhite] = 1.0;
      const std::vector<CandidateScore> ols = score_all(fit::NoiseWhitener(white, grid), r, grids, untried, 0, seed);
      std::size_t lead = 0;
      for (std::size_t i = 1; i < untried.size(); ++i)
        if (ols[i].share > ols[lead].share) lead = i;
      // 2. The noise identified with it as a fixed effect too.
      if (ols[lead].fitted) {
        leading = grids[untried[lead]].columns.col(static_cast<Eigen::Index>(ols[lead].best));
        noise = noise_of(grid, with_column(r.x, leading), y);
      }
    }
    // 3. Every candidate under that noise, and under each model it may as
    // well be (fit::plausible_models): the largest p of them, and the
    // family's largest effective number of tests. It sees an effect the
    // noise identified without it absorbed (a step read as a random walk);
    // the plausible models keep it from mistaking noise the record could
    // not pin down for an effect. (The noise identified without any
    // candidate is not a test of its own: a single point estimate, its
    // false alarms reached 10-13 % on a 75 h record; results/diagnosis_power.md.)
    const fit::NoiseWhitener whitener(noise, grid);
    double family_tests = 0.0;
    std::vector<CandidateScore> scores =
        score_all(whitener, r, grids, untried, options.draws, seed, &family_tests,
                  leftover_autoregression(whitener, r, leading, noise.blocks));
    std::vector<fit::NoiseWhitener> others;
    for (const fit::NoiseModel& m : fit::plausible_models(noise, grid)) {
      try {
        others.emplace_back(m, grid);
      } catch (const FitError&) {
      }
    }
    for (std::size_t m = 1; m < others.size(); ++m) {
      double tests = 0.0;
      const std::vector<CandidateScore> more =
          score_all(others[m], r, grids, untried, options.draws, seed, &tests,
                    leftover_autoregression(others[m], r, leading, noise.blocks));
      family_tests = std::max(family_tests, tests);
      for (std::size_t i = 0; i < scores.size(); ++i) {
        scores[i].p_value = std::max(scores[i].p_value, more[i].p_value);
        scores[i].p_bootstrap = std::max(scores[i].p_bootstrap, more[i].p_bootstrap);
      }
    }
    const auto level = [&](std::size_t j) { return family_level(options.alpha, grids[j].weight, family_tests); };
    std::vector<CandidateReport> round;
    std::vector<std::size_t> which;  // grid of each report
    std::vector<CandidateScore> round_scores;
    for (std::size_t i = 0; i < untried.size(); ++i) {
      const Grid& g = grids[untried[i]];
      const std::string name = g.term != nullptr ? std::string(g.term->name) : "step";
      if (!scores[i].fitted) {
        if (std::none_of(failed.begin(), failed.end(), [&](const auto& f) { return f.first == name; }))
          failed.emplace_back(name, "collinear with the model on this record");
        continue;
      }
      try {
        CandidateReport c = report_of(r, whitener, others, g, scores[i], level(untried[i]), block, options);
        c.round = round_number;
        round.push_back(std::move(c));
        which.push_back(untried[i]);
        round_scores.push_back(scores[i]);
      } catch (const FitError& e) {
        if (std::none_of(failed.begin(), failed.end(), [&](const auto& f) { return f.first == name; }))
          failed.emplace_back(name, e.what());
      }
    }
    if (round_number == 1) d.first_round = round;  // before resolve_rivals marks groups
    if (round.empty()) {
      noise = without;
      break;
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i < round.size(); ++i) {
      const bool better = round[i].significant != round[best].significant
                              ? round[i].significant
                              : round[i].likelihood_share > round[best].likelihood_share;
      if (better) best = i;
    }
    if (!round[best].significant) {
      std::stable_sort(round.begin(), round.end(), [](const CandidateReport& a, const CandidateReport& b) {
        return a.reduction_pct > b.reduction_pct;
      });
      for (const CandidateReport& c : round) d.candidates.push_back(c);
      noise = without;
      break;
    }
    const std::size_t leader = resolve_rivals(r, whitener, grids, which, round_scores, round, best, inseparable);
    d.candidates.push_back(round[leader]);
    const fit::Term* joined = round[leader].term;
    current.push_back(joined);
    params = fit::fit_parameters(data.derived, s.gyro_dph, current);
    r.x = fit::design_matrix(data.derived, current, params);
    r.sigma2 = round[leader].instability_after_dph * round[leader].instability_after_dph;
    const bool step = grids[which[leader]].term == nullptr;
    steps_joined += step;
    if (!step || steps_joined >= kMostSteps) std::erase(untried, which[leader]);
    // The noise was identified with the leader; another joined, or a
    // parameter moved: identify it again on the model as it now stands.
    noise = noise_of(grid, r.x, y);
  }
  noise.sensor = &data.units.kind();  // the components' names and units
  d.noise = std::make_shared<const fit::NoiseContext>(fit::NoiseContext{noise, grid});
  for (const auto& [name, why] : failed)
    d.skipped.push_back({.name = name, .reason = SkipReason::not_fitted, .error = why});
}

}  // namespace gyrotherm::studies::diagnosis_steps
