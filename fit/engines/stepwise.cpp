#include "fit/engines/stepwise.h"

#include <Eigen/Dense>
#include <boost/math/distributions/students_t.hpp>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

// Every option, once: parsing, validate() and the listing read this table.
const OptionTable<StepwiseOptions>& stepwise_option_table() {
  using O = StepwiseOptions;
  static const OptionTable<O> table{
      "stepwise",
      {ruled_row<O>("p_enter", "a term enters when its p-value is below this", &O::p_enter, number_above(0.0, 1.0)),
       ruled_row<O>("p_remove", "a term leaves when its p-value is above this (>= p_enter)", &O::p_remove,
                    number_above(0.0, 1.0))}};
  return table;
}

struct SubsetFit {
  Eigen::VectorXd beta;     // scaled coefficients of the subset, in its order
  Eigen::VectorXd p_value;  // per coefficient
};

SubsetFit fit_subset(const LinearProblem& problem, const std::vector<Eigen::Index>& subset) {
  const Eigen::Index k = static_cast<Eigen::Index>(subset.size());
  const double l = static_cast<double>(problem.points());
  Eigen::MatrixXd g(k, k);
  Eigen::VectorXd c(k);
  for (Eigen::Index a = 0; a < k; ++a) {
    c[a] = problem.cross()[subset[static_cast<std::size_t>(a)]];
    for (Eigen::Index b = 0; b < k; ++b)
      g(a, b) = problem.gram()(subset[static_cast<std::size_t>(a)], subset[static_cast<std::size_t>(b)]);
  }
  const Eigen::MatrixXd g_inv = g.ldlt().solve(Eigen::MatrixXd::Identity(k, k));
  SubsetFit fit;
  fit.beta = g_inv * c;
  const double s_yy = problem.sigma_y() * problem.sigma_y();
  const double rss = std::max(0.0, (l - 1.0) * (s_yy - c.dot(fit.beta)));
  const double dof = l - static_cast<double>(k) - 1.0;
  const double sigma2 = rss / dof;
  const boost::math::students_t t_dist(dof);
  fit.p_value.resize(k);
  for (Eigen::Index a = 0; a < k; ++a) {
    const double se = std::sqrt(std::max(0.0, sigma2 * g_inv(a, a) / (l - 1.0)));
    const double t = se > 0.0 ? std::abs(fit.beta[a]) / se : INFINITY;
    fit.p_value[a] =
        std::isfinite(t) ? 2.0 * boost::math::cdf(boost::math::complement(t_dist, t)) : 0.0;
  }
  return fit;
}

}  // namespace

FitResult StepwiseEngine::fit(const LinearProblem& problem, FitObserver* observer) const {
  const auto started = std::chrono::steady_clock::now();
  const auto m = static_cast<Eigen::Index>(problem.dimension());
  std::vector<bool> in(static_cast<std::size_t>(m), false);
  long fits = 0, steps = 0;
  std::vector<RunDetail::Step> steps_taken;
  auto subset_of = [&](Eigen::Index extra) {
    std::vector<Eigen::Index> s;
    for (Eigen::Index j = 0; j < m; ++j)
      if (in[static_cast<std::size_t>(j)] || j == extra) s.push_back(j);
    return s;
  };

  const long max_steps = 4 * m + 10;  // guards against cycling
  bool stopped = false;
  for (; steps < max_steps; ++steps) {
    // 2. The best term to enter.
    Eigen::Index best = -1;
    double best_p = options_.p_enter;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (in[static_cast<std::size_t>(j)]) continue;
      const std::vector<Eigen::Index> s = subset_of(j);
      const SubsetFit f = fit_subset(problem, s);
      ++fits;
      const auto pos = std::find(s.begin(), s.end(), j) - s.begin();
      if (f.p_value[pos] < best_p) {
        best_p = f.p_value[pos];
        best = j;
      }
    }
    if (best >= 0) {
      in[static_cast<std::size_t>(best)] = true;
      steps_taken.push_back({problem.term_names()[static_cast<std::size_t>(best)], true});
    } else {
      // 3. The worst term to remove.
      const std::vector<Eigen::Index> s = subset_of(-1);
      if (s.empty()) break;
      const SubsetFit f = fit_subset(problem, s);
      ++fits;
      Eigen::Index worst = -1;
      double worst_p = options_.p_remove;
      for (Eigen::Index a = 0; a < static_cast<Eigen::Index>(s.size()); ++a)
        if (f.p_value[a] > worst_p) {
          worst_p = f.p_value[a];
          worst = s[static_cast<std::size_t>(a)];
        }
      if (worst < 0) break;  // 4. nothing to add or remove
      in[static_cast<std::size_t>(worst)] = false;
      steps_taken.push_back({problem.term_names()[static_cast<std::size_t>(worst)], false});
    }
    if (observer != nullptr && !observer->on_iteration(steps + 1, fits, NAN)) {
      stopped = true;
      break;
    }
  }

  FitResult r;
  r.engine = "stepwise";
  r.z.assign(static_cast<std::size_t>(m), 0.0);
  r.inference.kept = in;
  r.inference.p_values.assign(static_cast<std::size_t>(m), 1.0);
  const std::vector<Eigen::Index> final_set = subset_of(-1);
  if (!final_set.empty()) {
    const SubsetFit f = fit_subset(problem, final_set);
    ++fits;
    for (std::size_t a = 0; a < final_set.size(); ++a) {
      const auto j = final_set[a];
      r.z[static_cast<std::size_t>(j)] = f.beta[static_cast<Eigen::Index>(a)] / problem.half_width()[j];
      r.inference.p_values[static_cast<std::size_t>(j)] = f.p_value[static_cast<Eigen::Index>(a)];
    }
  }
  // p-values of the terms left out: as if each were added to the final model.
  for (Eigen::Index j = 0; j < m; ++j) {
    if (in[static_cast<std::size_t>(j)]) continue;
    const std::vector<Eigen::Index> s = subset_of(j);
    const SubsetFit f = fit_subset(problem, s);
    ++fits;
    r.inference.p_values[static_cast<std::size_t>(j)] = f.p_value[std::find(s.begin(), s.end(), j) - s.begin()];
  }
  r.objective = problem.objective(r.z);
  r.evaluations = fits;
  r.iterations = steps;
  r.history = {{fits, r.objective}};
  r.termination = stopped ? Termination::stopped
                  : steps >= max_steps ? Termination::max_iterations
                                       : Termination::converged;
  r.detail.kind = RunDetail::Kind::stepwise;
  r.detail.steps = std::move(steps_taken);
  for (Eigen::Index j = 0; j < m; ++j)
    if (in[static_cast<std::size_t>(j)]) r.detail.kept.push_back(problem.term_names()[static_cast<std::size_t>(j)]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

void StepwiseOptions::validate() const {
  check_options(stepwise_option_table(), *this);
  if (p_remove < p_enter)
    throw InputError(fmt::format("stepwise options: p_remove={} must be >= p_enter={} (or a "
                                 "term could enter and leave forever)",
                                 p_remove, p_enter));
}

StepwiseEngine::StepwiseEngine(StepwiseOptions options) : options_(options) { options_.validate(); }

EngineInfo stepwise_engine_info() {
  return engine_info<StepwiseEngine>(
      "stepwise", "stepwise regression as MATLAB's stepwisefit (enter p<0.05, remove p>0.10)",
      /*stochastic=*/false, /*default_evaluations=*/0, &stepwise_option_table);
}

}  // namespace gyrotherm::fit
