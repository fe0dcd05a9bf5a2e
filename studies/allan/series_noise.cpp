#include "studies/allan/series_noise.h"

#include <algorithm>
#include <cmath>

#include "sim/util/input_error.h"

namespace gyrotherm::studies {

std::optional<fit::NoiseModel> identify_series_noise(std::span<const double> time_s,
                                                     std::span<const double> rate_dph, double tau0_s) {
  const std::size_t n = time_s.size();
  if (n < 16 || !(tau0_s > 0.0)) return std::nullopt;
  // About 512 windows over the record: about eight per block mean the
  // identification aggregates (it uses at most 64 by default), each a whole
  // number of samples; the model serves the τ beyond n/100 samples, far above a window.
  const std::size_t per = std::max<std::size_t>(1, n / 512);
  fit::WindowGrid grid;
  grid.window_s = static_cast<double>(per) * tau0_s;
  std::vector<double> means;
  std::size_t start = 0;
  while (start < n) {
    std::size_t end = start + 1;  // one window: `per` samples without a gap
    while (end < n && end - start < per && time_s[end] - time_s[end - 1] <= 1.5 * tau0_s) ++end;
    if (end - start == per) {
      double t = 0.0, y = 0.0;
      for (std::size_t i = start; i < end; ++i) {
        t += time_s[i];
        y += rate_dph[i];
      }
      grid.time_s.push_back(t / static_cast<double>(per));
      grid.averaging_s.push_back(grid.window_s);
      means.push_back(y / static_cast<double>(per));
    }
    start = end;
  }
  if (means.size() < 16) return std::nullopt;
  const auto count = static_cast<Eigen::Index>(means.size());
  try {
    return fit::identify_noise(grid, Eigen::MatrixXd(count, 0), Eigen::Map<const Eigen::VectorXd>(means.data(), count));
  } catch (const FitError&) {
    return std::nullopt;
  }
}

}  // namespace gyrotherm::studies
