#include "fit/engines/iafsa.h"

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

constexpr char kIafsa[] = "iafsa";
constexpr int kMaxIterations = 100000000;

using IafsaOptions = IafsaEngine::Options;

// Every option, once: parsing, validate() and the listing read this table
// (a function's static, so that it exists whenever the registry is built).
const OptionTable<IafsaOptions>& iafsa_option_table() {
  using O = IafsaOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{kIafsa,
                     {ruled_row<O>("fish", "N, the swarm size; auto is 8 up to 3 terms, 8 + 4·(m − 3) for m terms",
                                   &O::fish, whole_or_auto(2, 100000)),
                      ruled_row<O>("max_iterations",
                                   "G_max of eq. (5), also a stopping rule; auto is 700 up to 3 terms, "
                                   "700·2.5^(m − 3) for m terms",
                                   &O::max_iterations, whole_or_auto(1, kMaxIterations))}};
    std::vector<OptionRow<O>> school = fish_swarm::school_rows<O>("_0", "n/N");
    // Visual_min and Step_min after Visual_0 and Step_0, the schedule last.
    school.insert(school.begin() + 2,
                  {ruled_row<O>("visual_min", "Visual_min of eq. (5), fraction of the box width", &O::visual_min,
                                number_in(0.0, 1.0)),
                   ruled_row<O>("step_min", "Step_min of eq. (5), fraction of the box width", &O::step_min,
                                number_in(0.0, 1.0))});
    t.rows.insert(t.rows.end(), school.begin(), school.end());
    t.rows.push_back(ruled_row<O>("schedule", "eq. (5) as an update (compound) or from Visual_0, Step_0 (initial)",
                                  &O::schedule, one_of({"compound", "initial"})));
    return t;
  }();
  return table;
}

using fish_swarm::Fish;

// Other fish than `self` within Visual of `point`, over N.
double crowd(const fish_swarm::School& school, const std::vector<double>& point,
             std::size_t self, double crowding) {
  if (crowding >= 1.0) return 0.0;  // n ≤ N − 1 < N: never crowded
  const std::vector<Fish>& swarm = school.fish();
  int n = 0;
  for (std::size_t j = 0; j < swarm.size(); ++j)
    if (j != self && school.distance(swarm[j].x, point) < school.visual) ++n;
  return static_cast<double>(n) / static_cast<double>(swarm.size());
}

// One run: the paper's schedule and targets on top of the shared school
// (fit/engines/fish_swarm.h), whose evaluator's best point is the bulletin board.
FitResult run_iafsa(const IafsaEngine::Options& o, const LinearProblem& problem,
              FitObserver* observer) {
  fish_swarm::School school(problem, o.max_evaluations, o.target_objective, o.seed, streams::iafsa,
                            fish_swarm::PreyMove::jump_to, o.try_number);
  Evaluator& eval = school.evaluator();
  const std::size_t m = school.dimension();
  const std::size_t n = static_cast<std::size_t>(
      o.fish == IafsaEngine::kAuto ? IafsaEngine::auto_fish(m) : o.fish);
  const long g_last =
      o.max_iterations == IafsaEngine::kAuto ? IafsaEngine::auto_iterations(m) : o.max_iterations;
  const auto finish = [&](long iterations, Termination fallback) {
    return eval.result(kIafsa, iterations, fallback,
                       {.kind = RunDetail::Kind::fish_swarm,
                        .fish = static_cast<long>(n),
                        .iteration_limit = g_last,
                        .visual = school.visual / fish_swarm::kBoxWidth,
                        .step = school.step / fish_swarm::kBoxWidth});
  };

  // (2) Scatter the swarm over the box; (3) the evaluator's best point is the
  // bulletin board from the first evaluation on.
  school.visual = o.visual * fish_swarm::kBoxWidth;
  school.step = o.step * fish_swarm::kBoxWidth;
  if (!school.scatter(n)) return finish(0, Termination::max_iterations);
  std::vector<Fish>& swarm = school.fish();

  std::vector<double> centre(m);
  const double g_max = static_cast<double>(g_last);
  for (long g = 1; g <= g_last; ++g) {
    // (4) Eq. (5).
    const double alpha = std::exp(-3.0 * static_cast<double>(g) / g_max);
    if (o.schedule == "compound") {
      school.visual = school.visual * alpha + o.visual_min * fish_swarm::kBoxWidth;
      school.step = school.step * alpha + o.step_min * fish_swarm::kBoxWidth;
    } else {
      school.visual = o.visual * fish_swarm::kBoxWidth * alpha + o.visual_min * fish_swarm::kBoxWidth;
      school.step = o.step * fish_swarm::kBoxWidth * alpha + o.step_min * fish_swarm::kBoxWidth;
    }

    // The centre of the whole swarm, evaluated once for every fish.
    std::fill(centre.begin(), centre.end(), 0.0);
    for (const Fish& fish : swarm)
      for (std::size_t k = 0; k < m; ++k) centre[k] += fish.x[k] / static_cast<double>(n);
    const std::optional<double> f_centre = school.evaluate(centre);
    if (!f_centre) return finish(g, Termination::max_iterations);

    for (std::size_t i = 0; i < n; ++i) {
      const Fish& fish = swarm[i];
      // Swarm, eq. (3), towards the centre of the whole swarm.
      std::optional<Fish> swarmed;
      const double to_centre = school.distance(fish.x, centre);
      if (*f_centre < fish.f && to_centre > 0.0 &&
          crowd(school, centre, i, o.crowding) < o.crowding) {
        swarmed = school.move_towards(fish, centre, to_centre);
        if (!swarmed) return finish(g, Termination::max_iterations);
      }
      // Follow, eq. (4), towards the bulletin board (the swarm's best, which
      // the swarm move may just have improved).
      const std::vector<double> board = eval.best_point();
      std::optional<Fish> followed;
      const double to_board = school.distance(fish.x, board);
      if (eval.best() < fish.f && to_board > 0.0 &&
          crowd(school, board, i, o.crowding) < o.crowding) {
        followed = school.move_towards(fish, board, to_board);
        if (!followed) return finish(g, Termination::max_iterations);
      }
      // Prey is the default of both (once is enough when both fall back to
      // it); the behaviour with the smaller σ is kept.
      if (!school.settle(i, std::move(swarmed), std::move(followed)))
        return finish(g, Termination::max_iterations);
      // (5) The evaluator refreshed the bulletin board at every evaluation.
    }
    // (6)
    if (observer && !observer->on_iteration(g, eval.evaluations(), eval.best()))
      return finish(g, Termination::stopped);
  }
  return finish(g_last, Termination::max_iterations);
}

}  // namespace

void IafsaEngine::Options::validate() const {
  check_options(iafsa_option_table(), *this);
  check_stopping_rules(kIafsa, max_evaluations, target_objective);
}

int IafsaEngine::auto_fish(std::size_t terms) {
  return 8 + 4 * static_cast<int>(std::min<std::size_t>(terms > 3 ? terms - 3 : 0, 20000));
}

int IafsaEngine::auto_iterations(std::size_t terms) {
  const double extra = static_cast<double>(terms > 3 ? terms - 3 : 0);
  return static_cast<int>(std::min(700.0 * std::pow(2.5, extra), double{kMaxIterations}));
}

IafsaEngine::IafsaEngine(IafsaOptions options) : options_(std::move(options)) { options_.validate(); }

FitResult IafsaEngine::fit(const LinearProblem& problem, FitObserver* observer) const {
  return run_iafsa(options_, problem, observer);
}

EngineInfo iafsa_engine_info() {
  return engine_info<IafsaEngine>(kIafsa,
                                  "improved artificial fish swarm (Yu et al. 2014): shrinking Visual "
                                  "and Step, swarm to the swarm's centre, follow the bulletin board",
                                  /*stochastic=*/true, IafsaOptions{}.max_evaluations, &iafsa_option_table);
}

}  // namespace gyrotherm::fit
