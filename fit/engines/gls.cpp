// `gls`: generalised least squares under the record's identified noise.
//
//   β̂ = (X̃ᵀC⁻¹X̃)⁻¹ X̃ᵀC⁻¹ỹ   on the design with its intercept column, C the
//   window means' covariance of the noise identified on the least-squares
//   residual (LinearProblem::noise(), fit/model/noise_model.h), applied in
//   O(l·r) by its semi-separable Cholesky factor (fit/model/noise_whitening.h).
//
// Where the noise has memory (flicker, Gauss–Markov, random walk) GLS weighs
// the windows as the noise makes them informative, and its intervals are
// narrower than least squares' under the same honest covariance (measured in
// results/ols_coverage.md). It does not minimise the paper's σ of eq. (6):
// its residual's σ is a little above ols's, by design.
//
// 95 % intervals: the estimate's variance under each noise structure the
// record supports alike (the identified model and its alternatives, as ols's
// sandwich takes them), Var = A C' Aᵀ with
// A = (X̃ᵀC⁻¹X̃)⁻¹X̃ᵀC⁻¹, the widest per coefficient (covariance=widest, the
// default) or the point model's alone (covariance=model); Student t with
// least squares' Satterthwaite degrees of freedom under the same noise.
// Without an identified noise (too few windows) it is ols, and says so.
//
// Reference: Kariya & Kurata, Generalized Least Squares (Wiley 2004), ch. 2;
// the covariance of a GLS estimate under a misspecified C, ibid. §2.5.

#include <string>

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "fit/engines/engine.h"
#include "fit/engines/engine_options.h"
#include "fit/engines/ols.h"
#include "fit/model/linear_problem.h"
#include "fit/model/noise_model.h"
#include "fit/model/noise_whitening.h"

namespace gyrotherm::fit {

namespace {

struct GlsOptions {
  std::string covariance = "widest";  // widest (over the noise structures the record supports alike) or model
  void validate() const;
};

class GlsEngine : public Engine {
 public:
  explicit GlsEngine(GlsOptions options) : options_(std::move(options)) { options_.validate(); }
  FitResult fit(const LinearProblem& problem, FitObserver* observer) const override;

 private:
  GlsOptions options_;
};

const OptionTable<GlsOptions>& gls_option_table() {
  static const OptionTable<GlsOptions> table{"gls", {
      ruled_row<GlsOptions>("covariance", "widest (each interval the widest under the noise models the record "
                            "supports alike) or model (the identified model's alone)",
                            &GlsOptions::covariance, one_of({"widest", "model"})),
  }};
  return table;
}

void GlsOptions::validate() const { check_options(gls_option_table(), *this); }

// The variance of each coefficient of A·y (A = (XᵀC⁻¹X)⁻¹XᵀC⁻¹ on [1, X]) under
// each model, the widest kept.
Eigen::VectorXd widest_variances(const Eigen::MatrixXd& a_t, const std::vector<NoiseModel>& models,
                                 const WindowGrid& grid) {
  Eigen::VectorXd widest = Eigen::VectorXd::Zero(a_t.cols());
  for (const NoiseModel& model : models) {
    const Eigen::MatrixXd ca = model.apply(grid, a_t);
    for (Eigen::Index j = 0; j < a_t.cols(); ++j) widest[j] = std::max(widest[j], a_t.col(j).dot(ca.col(j)));
  }
  return widest;
}

}  // namespace

FitResult GlsEngine::fit(const LinearProblem& problem, FitObserver* observer) const {
  if (!problem.noise()) {
    FitResult r = OlsEngine{}.fit(problem, observer);
    r.engine = "gls";
    r.detail.kind = RunDetail::Kind::gls_without_noise;
    return r;
  }
  const auto started = std::chrono::steady_clock::now();
  const NoiseContext& noise = *problem.noise();
  const Eigen::MatrixXd& x = problem.scaled_design();
  const Eigen::Index l = x.rows(), m = x.cols();
  Eigen::MatrixXd design(l, m + 1);
  design << Eigen::VectorXd::Ones(l), x;
  const NoiseWhitener whitener(noise.model, noise.grid);
  const GlsFit g = gls(whitener, x, problem.centred_y());
  const Eigen::MatrixXd a_t = whitener.solve(design) * g.covariance;  // Aᵀ, l × (m + 1)
  // The model and the other structures the record supports alike (as ols's sandwich takes them).
  std::vector<NoiseModel> models = {noise.model};
  if (options_.covariance == "widest")
    models.insert(models.end(), noise.model.alternatives.begin(), noise.model.alternatives.end());
  const Eigen::VectorXd variance = widest_variances(a_t, models, noise.grid);
  const std::vector<double> dofs = noise_sandwich(noise.model, noise.grid, x).dof;

  FitResult r;
  r.engine = "gls";
  r.z.resize(static_cast<std::size_t>(m));
  for (Eigen::Index j = 0; j < m; ++j) r.z[static_cast<std::size_t>(j)] = g.beta[j + 1] / problem.half_width()[j];
  r.objective = problem.objective(r.z);
  r.evaluations = 1;
  r.iterations = 1;
  r.termination = Termination::exact;
  r.history = {{1, r.objective}};
  const Coefficients c = problem.physical(r.z);
  for (Eigen::Index j = 0; j < m; ++j) {
    const boost::math::students_t t_dist(dofs[static_cast<std::size_t>(j)]);
    const double t95 = boost::math::quantile(boost::math::complement(t_dist, 0.025));
    const double se_beta = std::sqrt(std::max(0.0, variance[j + 1]));
    const double se = se_beta / problem.scale()[j];
    const double b = c.b[static_cast<std::size_t>(j)];
    r.inference.intervals.push_back({b - t95 * se, b + t95 * se});
    const double t = se_beta > 0.0 ? std::abs(g.beta[j + 1]) / se_beta : INFINITY;
    r.inference.p_values.push_back(std::isfinite(t) ? 2.0 * boost::math::cdf(boost::math::complement(t_dist, t)) : 0.0);
  }
  r.inference.interval_method.kind = IntervalKind::gls;
  r.inference.interval_method.widest_of = options_.covariance == "widest" ? models.size() : 0;
  r.inference.interval_method.dof = *std::min_element(dofs.begin(), dofs.end());
  r.detail.kind = RunDetail::Kind::gls;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

EngineInfo gls_engine_info() {
  EngineInfo info = engine_info<GlsEngine>("gls",
                                "generalised least squares under the record's identified noise: narrower honest "
                                "intervals where the noise has memory",
                                           /*stochastic=*/false, /*default_evaluations=*/1, &gls_option_table);
  info.minimises_sigma = false;  // not in score's and reproduce's default engines
  return info;
}

}  // namespace gyrotherm::fit
