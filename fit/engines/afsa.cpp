#include "fit/engines/afsa.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fit/engines/fish_swarm.h"

namespace gyrotherm::fit {
namespace {

constexpr char kAfsa[] = "afsa";

using AfsaOptions = AfsaEngine::Options;

// Every option, once: parsing, validate() and the listing read this table
// (a function's static, so that it exists whenever the registry is built).
const OptionTable<AfsaOptions>& afsa_option_table() {
  using O = AfsaOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{kAfsa,
                     {ruled_row<O>("fish", "N, the swarm size", &O::fish, whole(2, 100000)),
                      ruled_row<O>("max_iterations", "iteration limit", &O::max_iterations, whole(1, 100000000))}};
    for (auto& row : fish_swarm::school_rows<O>("", "n_f/N")) t.rows.push_back(std::move(row));
    return t;
  }();
  return table;
}

using fish_swarm::Fish;

// One run: Li's choice of mates and targets on top of the shared school
// (fit/engines/fish_swarm.h), whose evaluator's best point is the bulletin board.
FitResult run_afsa(const AfsaEngine::Options& o, const LinearProblem& problem,
              FitObserver* observer) {
  fish_swarm::School school(problem, o.max_evaluations, o.target_objective, o.seed, streams::afsa,
                            fish_swarm::PreyMove::step_towards, o.try_number);
  school.visual = o.visual * fish_swarm::kBoxWidth;
  school.step = o.step * fish_swarm::kBoxWidth;
  const std::size_t n = static_cast<std::size_t>(o.fish);
  const std::size_t m = school.dimension();
  const auto finish = [&](long iterations, Termination fallback) {
    return school.evaluator().result(kAfsa, iterations, fallback,
                                     {.kind = RunDetail::Kind::fish_swarm,
                                      .fish = static_cast<long>(n),
                                      .iteration_limit = o.max_iterations,
                                      .visual = o.visual,
                                      .step = o.step});
  };

  // Scatter the swarm over the box; the evaluator's best point is the
  // bulletin board from the first evaluation on.
  if (!school.scatter(n)) return finish(0, Termination::max_iterations);
  std::vector<Fish>& swarm = school.fish();

  std::vector<double> centre(m);
  for (long g = 1; g <= o.max_iterations; ++g) {
    for (std::size_t i = 0; i < n; ++i) {
      const Fish& fish = swarm[i];
      // The mates within Visual: their number, centre and best.
      int n_f = 0;
      std::size_t best = i;
      std::fill(centre.begin(), centre.end(), 0.0);
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i || school.distance(swarm[j].x, fish.x) >= school.visual) continue;
        ++n_f;
        for (std::size_t k = 0; k < m; ++k) centre[k] += swarm[j].x[k];
        if (best == i || swarm[j].f < swarm[best].f) best = j;
      }
      const bool uncrowded =
          n_f >= 1 && static_cast<double>(n_f) / static_cast<double>(n) < o.crowding;

      // (2) Swarm, towards the mates' centre.
      std::optional<Fish> swarmed;
      if (uncrowded) {
        for (double& c : centre) c /= static_cast<double>(n_f);
        const std::optional<double> f_centre = school.evaluate(centre);
        if (!f_centre) return finish(g, Termination::max_iterations);
        const double to_centre = school.distance(fish.x, centre);
        if (*f_centre < fish.f && to_centre > 0.0) {
          swarmed = school.move_towards(fish, centre, to_centre);
          if (!swarmed) return finish(g, Termination::max_iterations);
        }
      }
      // (3) Follow, towards the best mate.
      std::optional<Fish> followed;
      if (uncrowded && swarm[best].f < fish.f) {
        const std::vector<double> leader = swarm[best].x;
        followed = school.move_towards(fish, leader, school.distance(fish.x, leader));
        if (!followed) return finish(g, Termination::max_iterations);
      }
      // (1) Prey stands in for a move whose test failed; the better move wins.
      if (!school.settle(i, std::move(swarmed), std::move(followed)))
        return finish(g, Termination::max_iterations);
    }
    if (observer && !observer->on_iteration(g, school.evaluator().evaluations(),
                                            school.evaluator().best()))
      return finish(g, Termination::stopped);
  }
  return finish(o.max_iterations, Termination::max_iterations);
}

}  // namespace

void AfsaEngine::Options::validate() const {
  check_options(afsa_option_table(), *this);
  check_stopping_rules(kAfsa, max_evaluations, target_objective);
}

AfsaEngine::AfsaEngine(AfsaOptions options) : options_(std::move(options)) { options_.validate(); }

FitResult AfsaEngine::fit(const LinearProblem& problem, FitObserver* observer) const {
  return run_afsa(options_, problem, observer);
}

EngineInfo afsa_engine_info() {
  return engine_info<AfsaEngine>(
      kAfsa, "artificial fish swarm (Li 2002): prey, swarm and follow within a fixed Visual and Step",
      /*stochastic=*/true, AfsaOptions{}.max_evaluations, &afsa_option_table);
}

}  // namespace gyrotherm::fit
