// Step 1's noise floor (studies/diagnose/diagnosis.h): a robust Hadamard
// deviation of the window means, or the scatter inside the windows.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/data/median.h"
#include "sim/util/input_error.h"
#include "studies/diagnose/diagnosis.h"
#include "sim/util/format.h"

namespace gyrotherm::studies {
namespace {

constexpr double kMedianChi2One = 0.454936;

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
    f.method = FloorMethod::hadamard;
    f.dph = f.hadamard_dph;
  } else if (f.within_dph > 0.0) {
    f.method = FloorMethod::within_window;
    f.dph = f.within_dph;
  } else {
    throw InputError(fmt::format(
        "only {} ({} equally spaced): too few to estimate the noise floor from "
        "the window means, and the windows hold too few samples to estimate it from their scatter",
        counted(s.size(), "window"), counted(f.triples, "triple")));
  }
  return f;
}

}  // namespace gyrotherm::studies
