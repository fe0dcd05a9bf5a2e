#pragma once
// AFSA: the artificial fish swarm algorithm of Li Xiaolei (2002), minimising
// σ(z) of LinearProblem over the unit box z ∈ [−1, 1]^m, as the paper
// (Yu et al. 2014, section 1) describes it before its improvements.
//
// N fish X_i, food f(X) = σ(X) (smaller is better), d_ij = ‖X_i − X_j‖, a
// fixed range Visual and maximum step Step (fractions of the box width, 2),
// crowding factor δ, Rand() uniform on (0, 1), U a vector uniform on [−1, 1]^m,
// and a bulletin board holding the best point ever evaluated.
//
// (1) Prey: up to try_number times pick X_j = X_i + Visual·U; at the first
//     with f(X_j) < f(X_i) step towards it,
//         X_next = X_i + Rand()·Step·(X_j − X_i)/‖X_j − X_i‖;
//     if none is better, take a random step X_next = X_i + Step·U.
// (2) Swarm: the n_f mates with d_ij < Visual have centre X_c (eq. 2). If
//     n_f ≥ 1, f(X_c) < f(X_i) and the centre is not crowded (n_f/N < δ),
//         X_next = X_i + Rand()·Step·(X_c − X_i)/‖X_c − X_i‖        (3)
//     else prey.
// (3) Follow: the best mate X_max with d_ij < Visual; if f(X_max) < f(X_i)
//     and n_f/N < δ,
//         X_next = X_i + Rand()·Step·(X_max − X_i)/‖X_max − X_i‖    (4)
//     else prey.
// Each iteration every fish, in turn, computes its swarm and follow moves
// (prey standing in for a move whose test fails; one prey serves both when
// both fail) and takes the one with the smaller σ. The bulletin board is
// refreshed at every evaluation. The run stops at the target σ, at the
// evaluation budget or after max_iterations. FitResult::iterations counts the
// iterations begun (the last may be cut short by the target or the budget);
// the observer hears after each completed one.
//
// With a fixed Visual and Step the swarm settles no finer than a fraction of
// Step: a small Step polishes well but travels slowly, a large one the
// reverse. IafsaEngine (fit/engines/iafsa.h) shrinks both as it goes. The moves
// themselves are shared with it in fit/engines/fish_swarm.h.
//
// Defaults (tuned on synthetic 3-term problems for the best σ after the
// default 20000 evaluations): 20 fish, Visual 0.5, Step 0.01, one prey
// attempt; σ ends a median ~1e-6 and at worst ~1e-4 (relative) above the
// least-squares optimum. δ = 1 turns crowding off: σ has a single minimum, and
// Li's δ = 0.618 left the swarm 10 % above it.
//
// References: Li Xiaolei, Shao Zhijiang, Qian Jixin, "An optimizing method
// based on autonomous animats: fish-swarm algorithm", Systems Engineering —
// Theory & Practice 22(11):32-38, 2002; Yu Xudong, Xu Yunong, Wei Guo, Long
// Xingwu, Infrared and Laser Engineering 43(1):81-87, 2014, section 1.

#include <cstdint>

#include "fit/engines/engine.h"

namespace gyrotherm::fit {

class AfsaEngine final : public Engine {
 public:
  struct Options {
    int fish = 20;                  // N, the swarm size
    int max_iterations = 1000;      // iteration limit (the default budget ends the run first)
    double visual = 0.5;            // Visual, fraction of the box width
    double step = 0.01;             // Step, fraction of the box width
    double crowding = 1.0;          // δ; a move is crowded when n_f/N ≥ δ (1: never)
    int try_number = 1;             // prey attempts before a random step
    std::uint64_t seed = 1;         // seeds the engine's own generator
    long max_evaluations = 20000;   // budget of objective evaluations
    double target_objective = 0.0;  // stop once σ ≤ this (0: no target)

    // Throws InputError naming the field, its value and the rule.
    void validate() const;
  };

  explicit AfsaEngine(Options options);
  FitResult fit(const LinearProblem& problem, FitObserver* observer = nullptr) const override;
  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace gyrotherm::fit
