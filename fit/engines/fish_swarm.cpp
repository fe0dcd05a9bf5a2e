#include "fit/engines/fish_swarm.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gyrotherm::fit::fish_swarm {

School::School(const LinearProblem& problem, long max_evaluations, double target_objective,
               std::uint64_t seed, std::uint64_t stream, PreyMove prey_move, int try_number)
    : eval_(problem, max_evaluations, target_objective),
      rng_(make_rng(seed, stream)),
      m_(problem.dimension()),
      prey_move_(prey_move),
      try_number_(try_number) {}

bool School::scatter(std::size_t n) {
  fish_.assign(n, Fish{std::vector<double>(m_, 0.0), 0.0});
  for (Fish& fish : fish_) {
    for (double& v : fish.x) v = unit_(rng_);
    const std::optional<double> f = evaluate(fish.x);
    if (!f) return false;
    fish.f = *f;
  }
  return true;
}

std::optional<double> School::evaluate(std::vector<double>& x) {
  if (eval_.done()) return std::nullopt;
  for (double& v : x) v = std::clamp(v, -1.0, 1.0);
  return eval_(x);
}

std::optional<Fish> School::move_towards(const Fish& fish, const std::vector<double>& target,
                                         double distance) {
  Fish next{fish.x, 0.0};
  const double length = rand01_(rng_) * step;
  for (std::size_t k = 0; k < m_; ++k) next.x[k] += length * (target[k] - fish.x[k]) / distance;
  const std::optional<double> f = evaluate(next.x);
  if (!f) return std::nullopt;
  next.f = *f;
  return next;
}

std::optional<Fish> School::prey(const Fish& fish) {
  Fish next{fish.x, 0.0};
  for (int t = 0; t < try_number_; ++t) {
    for (std::size_t k = 0; k < m_; ++k) next.x[k] = fish.x[k] + visual * unit_(rng_);
    const std::optional<double> f = evaluate(next.x);
    if (!f) return std::nullopt;
    if (*f >= fish.f) continue;
    if (prey_move_ == PreyMove::jump_to) {
      next.f = *f;
      return next;
    }
    const double d = distance(next.x, fish.x);
    if (d > 0.0) return move_towards(fish, next.x, d);
  }
  for (std::size_t k = 0; k < m_; ++k) next.x[k] = fish.x[k] + step * unit_(rng_);
  const std::optional<double> f = evaluate(next.x);
  if (!f) return std::nullopt;
  next.f = *f;
  return next;
}

bool School::settle(std::size_t i, std::optional<Fish> swarmed, std::optional<Fish> followed) {
  if (!swarmed || !followed) {
    std::optional<Fish> preyed = prey(fish_[i]);
    if (!preyed) return false;
    (swarmed ? followed : swarmed) = std::move(preyed);
  }
  // Both are there now, unless both fell back to the one prey (in swarmed).
  const bool follow = followed && (!swarmed || followed->f < swarmed->f);
  fish_[i] = std::move(follow ? *followed : *swarmed);
  return true;
}

double School::distance(const std::vector<double>& a, const std::vector<double>& b) const {
  double s = 0.0;
  for (std::size_t k = 0; k < m_; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(s);
}

}  // namespace gyrotherm::fit::fish_swarm
