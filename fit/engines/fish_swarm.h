#pragma once
// The mechanics that the two fish-swarm engines share (fit/engines/afsa.h for Li's
// AFSA, fit/engines/iafsa.h for the paper's IAFSA): a school of fish on the unit box
// z ∈ [−1, 1]^m of a LinearProblem, food f(X) = σ(X) (smaller is better), and
// the three moves of Yu et al. (2014), section 1:
//
//   move towards a target, eqs. (3) and (4):
//       X_next = X_i + Rand()·Step·(X_t − X_i)/‖X_t − X_i‖
//   prey, eq. (1): up to try_number times probe X_j = X_i + Visual·U; at the
//       first with f(X_j) < f(X_i) either step towards it as above (AFSA) or
//       move straight to it (IAFSA); if none is better, the random step
//       X_next = X_i + Step·U;
//   settle: a fish's swarm and follow moves are made where their tests pass,
//       prey stands in for a move whose test failed (one prey serves both),
//       and the fish becomes whichever has the smaller σ.
//
// Rand() is uniform on (0, 1), U a vector uniform on [−1, 1]^m; Visual and
// Step are in box coordinates (the box is 2 wide). What differs between the
// engines — which fish are mates, where the swarm and follow targets are, how
// Visual and Step change — stays in each engine, next to its description.
//
// Every evaluation goes through the Evaluator (its best point is the bulletin
// board), which refuses once the budget is spent or the target reached: a
// move that meets a refusal returns nullopt (settle returns false) and the
// engine's run unwinds.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <boost/random/uniform_real_distribution.hpp>

#include "fit/engines/engine.h"
#include "sim/util/random.h"

namespace gyrotherm::fit::fish_swarm {

// The box's width in its own coordinates ([−1, 1]^m): Visual and Step are
// fractions of it.
inline constexpr double kBoxWidth = 2.0;

// The options both swarms share, with their rules: Visual and Step as
// fractions of the box width (`start`: IAFSA's are the starting values,
// "_0"), δ of a neighbourhood's share `share` (Li's n_f/N, the paper's n/N)
// and the prey attempts. Options has visual, step, crowding and try_number.
template <class Options>
std::vector<OptionRow<Options>> school_rows(const std::string& start, const std::string& share) {
  using O = Options;
  const std::string width = ", fraction of the box width";
  return {ruled_row<O>("visual", "Visual" + start + width, &O::visual, number_above(0.0, 1.0)),
          ruled_row<O>("step", "Step" + start + width, &O::step, number_above(0.0, 1.0)),
          ruled_row<O>("crowding", "δ, crowded when " + share + " ≥ δ (1: never)", &O::crowding,
                       number_above(0.0, 1.0)),
          ruled_row<O>("try_number", "prey attempts before a random step", &O::try_number, whole(1, 1000))};
}

struct Fish {
  std::vector<double> x;
  double f = 0.0;
};

// How prey treats the first probe better than the fish.
enum class PreyMove {
  step_towards,  // AFSA: a step of Rand()·Step towards the probe
  jump_to,       // IAFSA: straight to the probe
};

class School {
 public:
  // The school's own generator is make_rng(seed, stream).
  School(const LinearProblem& problem, long max_evaluations, double target_objective,
         std::uint64_t seed, std::uint64_t stream, PreyMove prey_move, int try_number);

  // Scatters n fish uniformly over the box and evaluates them; false if the
  // evaluator refused.
  bool scatter(std::size_t n);

  // σ at x, clamped into the box in place; nullopt once the evaluator is done.
  std::optional<double> evaluate(std::vector<double>& x);

  // Eqs. (3) and (4); `distance` = ‖target − fish.x‖ > 0.
  std::optional<Fish> move_towards(const Fish& fish, const std::vector<double>& target,
                                   double distance);

  // Eq. (1).
  std::optional<Fish> prey(const Fish& fish);

  // Fish i becomes the better of `swarmed` and `followed`, prey filling in for
  // whichever is missing; false if the evaluator refused.
  bool settle(std::size_t i, std::optional<Fish> swarmed, std::optional<Fish> followed);

  double distance(const std::vector<double>& a, const std::vector<double>& b) const;

  std::vector<Fish>& fish() { return fish_; }
  const std::vector<Fish>& fish() const { return fish_; }
  Evaluator& evaluator() { return eval_; }
  std::size_t dimension() const { return m_; }

  // Visual and Step in box coordinates; the engine sets and changes them.
  double visual = 0.0;
  double step = 0.0;

 private:
  Evaluator eval_;
  Rng rng_;
  boost::random::uniform_real_distribution<double> unit_{-1.0, 1.0};
  boost::random::uniform_real_distribution<double> rand01_{0.0, 1.0};
  std::size_t m_;
  PreyMove prey_move_;
  int try_number_;
  std::vector<Fish> fish_;
};

}  // namespace gyrotherm::fit::fish_swarm
