#include "studies/diagnose/steps.h"

#include <algorithm>
#include <cmath>

namespace gyrotherm::fit {
namespace {

constexpr std::size_t kMinSide = 4;  // windows on each side of a step

// The OLS-CUSUM statistic of e[lo, hi) and where its maximum is (the first
// window after the kink).
struct Cusum {
  double statistic = 0;
  std::size_t split = 0;
};

Cusum cusum(const std::vector<double>& e, std::size_t lo, std::size_t hi) {
  const std::size_t n = hi - lo;
  double mean = 0.0;
  for (std::size_t p = lo; p < hi; ++p) mean += e[p];
  mean /= static_cast<double>(n);
  double var = 0.0, lag = 0.0;
  for (std::size_t p = lo; p < hi; ++p) {
    var += (e[p] - mean) * (e[p] - mean);
    if (p > lo) lag += (e[p] - mean) * (e[p - 1] - mean);
  }
  if (var <= 0.0) return {};
  const double rho = std::clamp(lag / var, -0.5, 0.9);
  const double long_run = var / static_cast<double>(n) * (1.0 + rho) / (1.0 - rho);
  Cusum c;
  double s = 0.0;
  for (std::size_t p = lo; p + 1 < hi; ++p) {
    s += e[p] - mean;
    const std::size_t split = p + 1;
    if (split - lo < kMinSide || hi - split < kMinSide) continue;
    const double k = std::abs(s) / std::sqrt(long_run * static_cast<double>(n));
    if (k > c.statistic) {
      c.statistic = k;
      c.split = split;
    }
  }
  return c;
}

void segment(const std::vector<double>& t, const std::vector<double>& e, std::size_t lo, std::size_t hi,
             double alpha, std::size_t max_steps, std::vector<StepCandidate>& out) {
  if (out.size() >= max_steps || hi - lo < 2 * kMinSide) return;
  const Cusum c = cusum(e, lo, hi);
  if (c.split == 0) return;
  const double p = kolmogorov_p(c.statistic);
  if (p >= alpha) return;
  out.push_back({std::round(0.5 * (t[c.split - 1] + t[c.split])), c.split, p});
  segment(t, e, lo, c.split, alpha, max_steps, out);
  segment(t, e, c.split, hi, alpha, max_steps, out);
}

}  // namespace

double kolmogorov_p(double x) {
  if (x <= 0.0) return 1.0;
  double p = 0.0;
  for (int m = 1; m <= 100; ++m) {
    const double term = std::exp(-2.0 * m * m * x * x);
    p += (m % 2 == 1 ? 2.0 : -2.0) * term;
    if (term < 1e-16) break;
  }
  return std::clamp(p, 0.0, 1.0);
}

std::vector<StepCandidate> find_steps(const std::vector<double>& time_s,
                                      const std::vector<double>& residual, double alpha,
                                      std::size_t max_steps) {
  std::vector<StepCandidate> out;
  segment(time_s, residual, 0, residual.size(), alpha, max_steps, out);
  std::sort(out.begin(), out.end(),
            [](const StepCandidate& a, const StepCandidate& b) { return a.time_s < b.time_s; });
  return out;
}

}  // namespace gyrotherm::fit
