#include "fit/engines/ols.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "fit/model/noise_bootstrap.h"
#include "fit/model/noise_model.h"
#include "sim/util/format.h"

namespace gyrotherm::fit {

namespace {

struct LongRunVariance {
  Eigen::MatrixXd S;        // long-run covariance of the scores, Σ_p Σ_q E[u_p u_qᵀ]
  double dof = 0.0;         // Student-t degrees of freedom (0: l − m − 1)
  IntervalKind kind = IntervalKind::newey_west;
  long lags = 0;            // the Bartlett kernel's lags, or the cosine frequencies
};

LongRunVariance prewhitened_newey_west(const Eigen::MatrixXd& u) {
  const Eigen::Index l = u.rows(), m = u.cols();
  // Pre-whitened Newey–West HAC covariance (Andrews & Monahan 1992):
  // u_p = e_p x̃_p; a VAR(1) u_p = A u_{p−1} + w_p takes out most of the
  // persistence, the Bartlett-kernel sum runs on w with Andrews' bandwidth,
  // and S = (I − A)⁻¹ S_w (I − A)⁻ᵀ re-colours it.
  const Eigen::MatrixXd u_now = u.bottomRows(l - 1), u_before = u.topRows(l - 1);
  Eigen::MatrixXd A = (u_now.transpose() * u_before) *
                      (u_before.transpose() * u_before).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  // Keep the VAR stable (eigenvalues of A inside 0.97), as Andrews & Monahan do.
  {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::VectorXd sv = svd.singularValues();
    if (sv.maxCoeff() > 0.97) {
      for (Eigen::Index k = 0; k < sv.size(); ++k) sv[k] = std::min(sv[k], 0.97);
      A = svd.matrixU() * sv.asDiagonal() * svd.matrixV().transpose();
    }
  }
  const Eigen::MatrixXd w = u_now - u_before * A.transpose();
  const Eigen::Index n = w.rows();
  // Andrews' AR(1) plug-in bandwidth for the Bartlett kernel, on the whitened series.
  double num = 0.0, den = 0.0;
  for (Eigen::Index j = 0; j < m; ++j) {
    double c0 = 0.0, c1 = 0.0;
    for (Eigen::Index p = 0; p < n; ++p) {
      c0 += w(p, j) * w(p, j);
      if (p > 0) c1 += w(p, j) * w(p - 1, j);
    }
    const double rho_j = std::clamp(c0 > 0.0 ? c1 / c0 : 0.0, -0.97, 0.97);
    const double s2 = c0 / static_cast<double>(n) * (1.0 - rho_j * rho_j);
    num += 4.0 * rho_j * rho_j * s2 * s2 / std::pow(1.0 - rho_j, 6) / std::pow(1.0 + rho_j, 2);
    den += s2 * s2 / std::pow(1.0 - rho_j, 4);
  }
  const double alpha = den > 0.0 ? num / den : 0.0;
  const auto lags = static_cast<Eigen::Index>(std::min<double>(
      std::ceil(1.1447 * std::cbrt(alpha * static_cast<double>(n))), static_cast<double>(n / 2)));
  Eigen::MatrixXd S_w = w.transpose() * w;
  for (Eigen::Index lag = 1; lag <= lags; ++lag) {
    const double weight = 1.0 - static_cast<double>(lag) / static_cast<double>(lags + 1);
    const Eigen::MatrixXd gamma = w.bottomRows(n - lag).transpose() * w.topRows(n - lag);
    S_w += weight * (gamma + gamma.transpose());
  }
  const Eigen::MatrixXd recolour =
      (Eigen::MatrixXd::Identity(m, m) - A).fullPivLu().inverse();
  Eigen::MatrixXd S = recolour * S_w * recolour.transpose();
  S *= static_cast<double>(l) / static_cast<double>(l - m - 1);
  return {S, 0.0, IntervalKind::newey_west, static_cast<long>(lags)};
}

// Equal-weighted cosine estimator: the scores projected on the B lowest
// cosine frequencies, Λ_j = sqrt(2/l) Σ_p u_p cos(π j (p + ½)/l); each Λ_j has
// the long-run covariance Ω of one score, so S = l·Ω̂ = (l/B) Σ_j Λ_j Λ_jᵀ.
LongRunVariance equal_weighted_cosine(const Eigen::MatrixXd& u, int terms) {
  const Eigen::Index l = u.rows(), m = u.cols();
  const int b = terms > 0 ? terms
                          : static_cast<int>(std::ceil(0.4 * std::pow(static_cast<double>(l), 2.0 / 3.0)));
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd lambda(m);
  for (int j = 1; j <= b; ++j) {
    lambda.setZero();
    for (Eigen::Index p = 0; p < l; ++p)
      lambda += std::sqrt(2.0 / static_cast<double>(l)) *
                std::cos(M_PI * j * (static_cast<double>(p) + 0.5) / static_cast<double>(l)) *
                u.row(p).transpose();
    S += lambda * lambda.transpose();
  }
  S *= static_cast<double>(l) / static_cast<double>(b);
  return {S, static_cast<double>(b), IntervalKind::cosine, b};
}

}  // namespace

std::vector<double> least_squares_optimum(const LinearProblem& problem) {
  const Eigen::VectorXd beta =
      problem.scaled_design().colPivHouseholderQr().solve(problem.centred_y());
  std::vector<double> z(problem.dimension());
  for (std::size_t j = 0; j < z.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    z[j] = beta[jj] / problem.half_width()[jj];
  }
  return z;
}

FitResult OlsEngine::fit(const LinearProblem& problem, FitObserver*) const {
  const auto started = std::chrono::steady_clock::now();
  const Eigen::MatrixXd& X = problem.scaled_design();
  const Eigen::Index l = X.rows(), m = X.cols();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  const Eigen::VectorXd beta = qr.solve(problem.centred_y());
  const Eigen::VectorXd e = problem.centred_y() - X * beta;

  FitResult r;
  r.engine = "ols";
  r.z.resize(static_cast<std::size_t>(m));
  for (Eigen::Index j = 0; j < m; ++j)
    r.z[static_cast<std::size_t>(j)] = beta[j] / problem.half_width()[j];
  r.objective = problem.objective(r.z);
  r.evaluations = 1;
  r.iterations = 1;
  r.termination = Termination::exact;
  r.history = {{1, r.objective}};

  double e_num = 0.0, e_den = 0.0;
  for (Eigen::Index p = 0; p < l; ++p) {
    e_den += e[p] * e[p];
    if (p > 0) e_num += e[p] * e[p - 1];
  }
  const double rho = e_den > 0.0 ? e_num / e_den : 0.0;

  const bool from_noise = options_.intervals != "nw" && options_.intervals != "ewc" && problem.noise();
  const bool bootstrap =
      from_noise && (options_.intervals == "bootstrap" ||
                     (options_.intervals == "auto" &&
                      bootstrap_by_default(problem.noise()->model, problem.noise()->grid, X)));
  IntervalMethod& method = r.inference.interval_method;
  if (bootstrap) {
    const NoiseContext& noise = *problem.noise();
    const NoiseBootstrap boot = noise_bootstrap(noise.model, noise.grid, X, options_.draws, options_.seed);
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto [lo, hi] = boot.interval(j, beta[j]);
      r.inference.intervals.push_back({lo / problem.scale()[j], hi / problem.scale()[j]});
      r.inference.p_values.push_back(boot.p_value(j, beta[j]));
    }
    method.kind = IntervalKind::noise_bootstrap;
    method.draws = options_.draws;
  } else {
    Eigen::MatrixXd V;
    std::vector<double> dofs;
    if (from_noise) {
      // The identified noise's covariance (fit/model/noise_model.h).
      const NoiseContext& noise = *problem.noise();
      NoiseSandwich sandwich = noise_sandwich(noise.model, noise.grid, X);
      V = std::move(sandwich.covariance);
      dofs = std::move(sandwich.dof);
      method.kind = IntervalKind::noise_covariance;
      method.dof = *std::min_element(dofs.begin(), dofs.end());
    } else {
      const Eigen::MatrixXd u = X.array().colwise() * e.array();  // rows: e_p x̃_p
      const LongRunVariance lrv = options_.intervals == "ewc"
                                      ? equal_weighted_cosine(u, options_.ewc_terms)
                                      : prewhitened_newey_west(u);
      const Eigen::MatrixXd xtx_inv =
          (X.transpose() * X).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
      V = xtx_inv * lrv.S * xtx_inv;
      dofs.assign(static_cast<std::size_t>(m), lrv.dof > 0 ? lrv.dof : static_cast<double>(l - m - 1));
      method.kind = lrv.kind;
      method.lags = lrv.lags;
      method.no_noise_model = options_.intervals != "nw" && options_.intervals != "ewc";
      method.dof = dofs.front();
    }
    const Coefficients c = problem.physical(r.z);
    for (Eigen::Index j = 0; j < m; ++j) {
      const boost::math::students_t t_dist(dofs[static_cast<std::size_t>(j)]);
      const double t95 = boost::math::quantile(boost::math::complement(t_dist, 0.025));
      const double se_beta = std::sqrt(std::max(0.0, V(j, j)));
      const double se = se_beta / problem.scale()[j];
      const double b = c.b[static_cast<std::size_t>(j)];
      r.inference.intervals.push_back({b - t95 * se, b + t95 * se});
      const double t = se_beta > 0.0 ? std::abs(beta[j]) / se_beta : INFINITY;
      r.inference.p_values.push_back(std::isfinite(t) ? 2.0 * boost::math::cdf(boost::math::complement(t_dist, t))
                                            : 0.0);
    }
  }
  method.has_lag1 = true;
  method.lag1_autocorrelation = rho;
  r.detail.kind = RunDetail::Kind::qr;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

namespace {

// Every option, once: parsing, validate() and the listing read this table.
const OptionTable<OlsOptions>& ols_option_table() {
  using O = OlsOptions;
  static const OptionTable<O> table{
      "ols",
      {ruled_row<O>("intervals",
                    "auto (bootstrap on a record of fewer than 200 windows or under random-walk-dominated noise, "
                    "else model), model (analytic, from the record's identified noise; nw where none is "
                    "identified), bootstrap (drawn from the noise models the record supports), nw (pre-whitened "
                    "Newey-West) or ewc (equal-weighted cosine)",
                    &O::intervals, one_of({"auto", "model", "bootstrap", "nw", "ewc"})),
       ruled_row<O>("draws", "bootstrap draws (intervals=bootstrap)", &O::draws, whole(100, 100000)),
       ruled_row<O>("ewc_terms", "cosine terms B for ewc (0: ceil(0.4 l^(2/3)))", &O::ewc_terms, whole(0, 1000))}};
  return table;
}

}  // namespace

void OlsOptions::validate() const { check_options(ols_option_table(), *this); }

OlsEngine::OlsEngine(OlsOptions options) : options_(std::move(options)) { options_.validate(); }

EngineInfo ols_engine_info() {
  return engine_info<OlsEngine>(
      "ols", "exact least squares (QR) with autocorrelation-robust 95 % intervals: the reference",
      /*stochastic=*/false, /*default_evaluations=*/1, &ols_option_table);
}

}  // namespace gyrotherm::fit
