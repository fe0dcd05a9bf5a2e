#include "studies/diagnose/likelihood_test.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/special_functions/beta.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <vector>

#include "sim/util/random.h"

namespace gyrotherm::studies {

double LikelihoodTest::single_p(double share, double dof) {
  if (!(share > 0.0)) return 1.0;
  if (share >= 1.0) return 0.0;
  if (dof < 2.0) return 1.0;  // nothing left to test against
  return boost::math::ibetac(0.5, 0.5 * (dof - 1.0), share);
}

LikelihoodTest::LikelihoodTest(const fit::NoiseWhitener& whitener, const Eigen::MatrixXd& model,
                               const Eigen::VectorXd& y)
    : whitener_(whitener) {
  const Eigen::Index l = y.size();
  Eigen::MatrixXd design(l, model.cols() + 1);
  design.col(0).setOnes();
  design.rightCols(model.cols()) = model;
  const Eigen::MatrixXd xw = whitener_.whiten(design);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(xw);
  const Eigen::Index rank = qr.rank();
  q_ = (qr.householderQ() * Eigen::MatrixXd::Identity(l, xw.cols())).leftCols(rank);
  const Eigen::VectorXd yw = whitener_.whiten(y);
  e_ = yw - q_ * (q_.transpose() * yw);
  rss_ = e_.squaredNorm();
  dof_ = static_cast<double>(l - rank);
  columns_.resize(l, 0);
}

namespace {

// The rate n of V = −ln(1 − p_min) as the draws show it in their lower tail
// (small p, where the tests are decided): the maximum-likelihood rate of an
// exponential censored at the k-th smallest draw, k a twentieth of the draws
// (at least 10). For independent tests V is exponential at every v and this
// is the plain estimate's n; for strongly correlated ones (a step's
// positions under white noise) the effective number grows as p falls, and
// the mean of all draws would set n too low and p too small.
double tail_rate(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size(), std::max<std::size_t>(10, v.size() / 20));
  double sum = 0.0;
  for (std::size_t i = 0; i < k; ++i) sum += v[i];
  sum += static_cast<double>(v.size() - k) * v[k - 1];
  return sum > 0.0 ? static_cast<double>(k) / sum : 0.0;
}

}  // namespace

double family_level(double alpha, double weight, double family_tests) {
  return weight * -std::expm1(std::log1p(-alpha) / std::max(family_tests, 1e-12));
}

std::size_t LikelihoodTest::add(const Eigen::MatrixXd& columns, double weight) {
  const std::size_t index = scores_.size();
  weights_.push_back(weight);
  family_tests_ += weight;
  CandidateScore s;
  Eigen::MatrixXd w = whitener_.whiten(columns);
  const Eigen::VectorXd before = w.colwise().squaredNorm();
  w -= q_ * (q_.transpose() * w);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index c = 0; c < w.cols(); ++c) {
    const double norm2 = w.col(c).squaredNorm();
    // A column (nearly) in the model's span carries nothing new.
    if (!(norm2 > 1e-10 * before[c]) || !std::isfinite(norm2)) continue;
    w.col(c) /= std::sqrt(norm2);
    const double share = rss_ > 0.0 ? std::pow(w.col(c).dot(e_), 2) / rss_ : 0.0;
    if (!s.fitted || share > s.share) {
      s.share = share;
      s.best = static_cast<std::size_t>(c);
    }
    s.fitted = true;
    kept.push_back(c);
  }
  if (!kept.empty()) {
    const Eigen::Index old = columns_.cols();
    columns_.conservativeResize(Eigen::NoChange, old + static_cast<Eigen::Index>(kept.size()));
    for (std::size_t k = 0; k < kept.size(); ++k) {
      columns_.col(old + static_cast<Eigen::Index>(k)) = w.col(kept[k]);
      owner_.push_back(index);
      grid_index_.push_back(static_cast<std::size_t>(kept[k]));
    }
  }
  s.p_value = s.fitted ? single_p(s.share, dof_) : 1.0;
  scores_.push_back(s);
  return index;
}

Eigen::VectorXd residual_autoregression(const Eigen::VectorXd& e, int most_order) {
  const Eigen::Index l = e.size();
  const int top = std::clamp<int>(most_order, 0, static_cast<int>(l / 4));
  if (top < 1) return {};
  std::vector<double> r(static_cast<std::size_t>(top) + 1, 0.0);
  for (int k = 0; k <= top; ++k)
    r[static_cast<std::size_t>(k)] = e.head(l - k).dot(e.tail(l - k)) / static_cast<double>(l);
  if (!(r[0] > 0.0)) return {};
  // Levinson–Durbin: order k's coefficients and innovation variance.
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(top), best;
  double variance = r[0];
  double best_aic = static_cast<double>(l) * std::log(variance);
  for (int k = 1; k <= top; ++k) {
    double acc = r[static_cast<std::size_t>(k)];
    for (int j = 1; j < k; ++j) acc -= phi[j - 1] * r[static_cast<std::size_t>(k - j)];
    const double reflection = acc / variance;
    Eigen::VectorXd next = phi;
    next[k - 1] = reflection;
    for (int j = 1; j < k; ++j) next[j - 1] = phi[j - 1] - reflection * phi[k - j - 1];
    phi = next;
    variance *= 1.0 - reflection * reflection;
    if (!(variance > 0.0)) break;
    const double aic = static_cast<double>(l) * std::log(variance) + 2.0 * k;
    if (aic < best_aic) {
      best_aic = aic;
      best = phi.head(k);
    }
  }
  return best;
}

void LikelihoodTest::calibrate(int draws, std::uint64_t seed, const Eigen::VectorXd& ar) {
  if (scores_.empty() || columns_.cols() == 0 || draws < 1) return;
  const Eigen::Index l = columns_.rows();
  Rng rng = make_rng(seed, streams::diagnosis_likelihood_bootstrap);
  boost::random::normal_distribution<double> normal;
  Eigen::MatrixXd e(l, draws);
  // Each draw through the autoregression from rest, after a burn-in long
  // enough for it to forget the start (none without one: plain normals).
  const Eigen::Index order = ar.size(), burn = 20 * order;
  std::vector<double> x(static_cast<std::size_t>(burn + l));
  for (Eigen::Index b = 0; b < draws; ++b) {
    for (Eigen::Index t = 0; t < burn + l; ++t) {
      double v = normal(rng);
      for (Eigen::Index j = 1; j <= std::min(order, t); ++j) v += ar[j - 1] * x[static_cast<std::size_t>(t - j)];
      x[static_cast<std::size_t>(t)] = v;
    }
    for (Eigen::Index i = 0; i < l; ++i) e(i, b) = x[static_cast<std::size_t>(burn + i)];
  }
  e -= q_ * (q_.transpose() * e);
  const Eigen::RowVectorXd norms = e.colwise().squaredNorm();
  const Eigen::MatrixXd dots = columns_.transpose() * e;  // columns × draws
  // Per candidate, each draw's largest share over its grid.
  Eigen::MatrixXd largest = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(scores_.size()), draws);
  for (Eigen::Index c = 0; c < dots.rows(); ++c) {
    const auto j = static_cast<Eigen::Index>(owner_[static_cast<std::size_t>(c)]);
    largest.row(j) = largest.row(j).cwiseMax(dots.row(c).array().square().matrix().cwiseQuotient(norms));
  }
  std::vector<std::size_t> grid_size(scores_.size(), 0);
  for (std::size_t o : owner_) ++grid_size[o];
  for (std::size_t j = 0; j < scores_.size(); ++j) {
    CandidateScore& s = scores_[j];
    if (!s.fitted) continue;
    const auto jj = static_cast<Eigen::Index>(j);
    int above = 0;
    std::vector<double> v(static_cast<std::size_t>(draws));
    for (Eigen::Index b = 0; b < draws; ++b) {
      above += largest(jj, b) >= s.share;
      v[static_cast<std::size_t>(b)] = -std::log1p(-std::min(single_p(largest(jj, b), dof_), 1.0 - 1e-16));
    }
    s.p_bootstrap = (above + 1.0) / (draws + 1.0);
    const double rate = tail_rate(std::move(v));
    s.tests = (grid_size[j] == 1 && order == 0) || !(rate > 0.0) ? 1.0 : std::max(1.0, rate);
    s.p_value = -std::expm1(s.tests * std::log1p(-single_p(s.share, dof_)));
  }
  // The family: each draw's smallest p_j/w_j over the candidates, Q_b, and
  // W_eff the tail rate of −ln(1 − Q_b), within [the largest weight, W].
  double heaviest = 0.0;
  for (std::size_t j = 0; j < scores_.size(); ++j)
    if (scores_[j].fitted) heaviest = std::max(heaviest, weights_[j]);
  if (!(heaviest > 0.0)) return;
  std::vector<double> v(static_cast<std::size_t>(draws));
  for (Eigen::Index b = 0; b < draws; ++b) {
    double q = 1.0;
    for (std::size_t j = 0; j < scores_.size(); ++j) {
      const CandidateScore& s = scores_[j];
      if (!s.fitted || !(weights_[j] > 0.0)) continue;
      const double p = -std::expm1(s.tests * std::log1p(-single_p(largest(static_cast<Eigen::Index>(j), b), dof_)));
      q = std::min(q, p / weights_[j]);
    }
    v[static_cast<std::size_t>(b)] = -std::log1p(-std::min(q, 1.0 - 1e-16));
  }
  if (const double rate = tail_rate(std::move(v)); rate > 0.0) family_tests_ = std::clamp(rate, heaviest, family_tests_);
}

}  // namespace gyrotherm::studies
