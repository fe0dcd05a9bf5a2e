#include "fit/iafsa.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <boost/random/uniform_real_distribution.hpp>

#include "sim/input_error.h"
#include "sim/random.h"

namespace gyrotherm::fit {
namespace {

constexpr char kName[] = "iafsa";
// The engine's stream of make_rng(seed, stream): its own numbers, whatever
// other components draw from the same seed.
constexpr std::uint64_t kStream = 0x1AF5A;
constexpr double kBoxWidth = 2.0;

// The one place the option rules live: make() reads KEY=VALUE strings with
// them and validate() checks an Options aggregate with the same reader.
void read_options(OptionReader& reader, IafsaEngine::Options& o) {
  reader.integer("fish", o.fish, 2, 100000);
  reader.integer("max_iterations", o.max_iterations, 1, 100000000);
  reader.real("visual", o.visual, 0.0, 1.0, true);
  reader.real("step", o.step, 0.0, 1.0, true);
  reader.real("visual_min", o.visual_min, 0.0, 1.0);
  reader.real("step_min", o.step_min, 0.0, 1.0);
  reader.real("crowding", o.crowding, 0.0, 1.0, true);
  reader.integer("try_number", o.try_number, 1, 1000);
  reader.choice("schedule", o.schedule, {"compound", "initial"});
}

struct Fish {
  std::vector<double> x;
  double f = 0.0;
};

// One run: the swarm, the generator and the evaluator (whose best point is
// the bulletin board). Every evaluation goes through evaluate(), which
// refuses once the budget is spent or the target reached; a behaviour that
// meets a refusal returns nullopt and the run unwinds.
class Run {
 public:
  Run(const IafsaEngine::Options& o, const LinearProblem& problem)
      : o_(o),
        eval_(problem, o.max_evaluations, o.target_objective),
        rng_(sim::make_rng(o.seed, kStream)),
        m_(problem.dimension()) {}

  FitResult go(FitObserver* observer);

 private:
  std::optional<double> evaluate(std::vector<double>& x) {
    if (eval_.done()) return std::nullopt;
    for (double& v : x) v = std::clamp(v, -1.0, 1.0);
    return eval_(x);
  }

  // Prey, eq. (1): X_j = X_i + Visual·U up to try_number times; IAFSA moves
  // straight to the first better X_j. Otherwise a random step.
  std::optional<Fish> prey(const Fish& fish) {
    Fish next{fish.x, 0.0};
    for (int t = 0; t < o_.try_number; ++t) {
      for (std::size_t k = 0; k < m_; ++k) next.x[k] = fish.x[k] + visual_ * unit_(rng_);
      const std::optional<double> f = evaluate(next.x);
      if (!f) return std::nullopt;
      if (*f < fish.f) {
        next.f = *f;
        return next;
      }
    }
    for (std::size_t k = 0; k < m_; ++k) next.x[k] = fish.x[k] + step_ * unit_(rng_);
    const std::optional<double> f = evaluate(next.x);
    if (!f) return std::nullopt;
    next.f = *f;
    return next;
  }

  // Eqs. (3) and (4): a step of Rand()·Step along the unit vector to `target`.
  std::optional<Fish> move_towards(const Fish& fish, const std::vector<double>& target,
                                   double distance) {
    Fish next{fish.x, 0.0};
    const double length = rand01_(rng_) * step_;
    for (std::size_t k = 0; k < m_; ++k)
      next.x[k] += length * (target[k] - fish.x[k]) / distance;
    const std::optional<double> f = evaluate(next.x);
    if (!f) return std::nullopt;
    next.f = *f;
    return next;
  }

  double distance(const std::vector<double>& a, const std::vector<double>& b) const {
    double s = 0.0;
    for (std::size_t k = 0; k < m_; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
    return std::sqrt(s);
  }

  // Other fish than `self` within Visual of `point`, over N.
  double crowd(const std::vector<double>& point, std::size_t self) const {
    if (o_.crowding >= 1.0) return 0.0;  // n ≤ N − 1 < N: never crowded
    int n = 0;
    for (std::size_t j = 0; j < swarm_.size(); ++j)
      if (j != self && distance(swarm_[j].x, point) < visual_) ++n;
    return static_cast<double>(n) / static_cast<double>(swarm_.size());
  }

  const IafsaEngine::Options& o_;
  Evaluator eval_;
  sim::Rng rng_;
  boost::random::uniform_real_distribution<double> unit_{-1.0, 1.0};
  boost::random::uniform_real_distribution<double> rand01_{0.0, 1.0};
  std::size_t m_;
  std::vector<Fish> swarm_;
  double visual_ = 0.0;  // in box coordinates (the width is 2)
  double step_ = 0.0;
};

FitResult Run::go(FitObserver* observer) {
  const std::size_t n = static_cast<std::size_t>(o_.fish);
  const auto finish = [&](long iterations, Termination fallback) {
    return eval_.result(kName, iterations, fallback,
                        fmt::format("{} fish, {} of {} iterations; Visual {:.3g}, Step {:.3g} "
                                    "(box widths)",
                                    n, iterations, o_.max_iterations, visual_ / kBoxWidth,
                                    step_ / kBoxWidth));
  };

  // (2) Scatter the swarm over the box; (3) the evaluator's best point is the
  // bulletin board from the first evaluation on.
  visual_ = o_.visual * kBoxWidth;
  step_ = o_.step * kBoxWidth;
  swarm_.assign(n, Fish{std::vector<double>(m_, 0.0), 0.0});
  for (Fish& fish : swarm_) {
    for (double& v : fish.x) v = unit_(rng_);
    const std::optional<double> f = evaluate(fish.x);
    if (!f) return finish(0, Termination::max_iterations);
    fish.f = *f;
  }

  std::vector<double> centre(m_);
  const double g_max = static_cast<double>(o_.max_iterations);
  for (long g = 1; g <= o_.max_iterations; ++g) {
    // (4) Eq. (5).
    const double alpha = std::exp(-3.0 * static_cast<double>(g) / g_max);
    if (o_.schedule == "compound") {
      visual_ = visual_ * alpha + o_.visual_min * kBoxWidth;
      step_ = step_ * alpha + o_.step_min * kBoxWidth;
    } else {
      visual_ = o_.visual * kBoxWidth * alpha + o_.visual_min * kBoxWidth;
      step_ = o_.step * kBoxWidth * alpha + o_.step_min * kBoxWidth;
    }

    // The centre of the whole swarm, evaluated once for every fish.
    std::fill(centre.begin(), centre.end(), 0.0);
    for (const Fish& fish : swarm_)
      for (std::size_t k = 0; k < m_; ++k) centre[k] += fish.x[k] / static_cast<double>(n);
    const std::optional<double> f_centre = evaluate(centre);
    if (!f_centre) return finish(g, Termination::max_iterations);

    for (std::size_t i = 0; i < n; ++i) {
      const Fish& fish = swarm_[i];
      // Swarm, eq. (3), towards the centre of the whole swarm.
      std::optional<Fish> swarmed;
      bool swarm_moved = false;
      const double to_centre = distance(fish.x, centre);
      if (*f_centre < fish.f && to_centre > 0.0 && crowd(centre, i) < o_.crowding) {
        swarmed = move_towards(fish, centre, to_centre);
        if (!swarmed) return finish(g, Termination::max_iterations);
        swarm_moved = true;
      }
      // Follow, eq. (4), towards the bulletin board (the swarm's best).
      const std::vector<double> board = eval_.best_point();
      std::optional<Fish> followed;
      bool follow_moved = false;
      const double to_board = distance(fish.x, board);
      if (eval_.best() < fish.f && to_board > 0.0 && crowd(board, i) < o_.crowding) {
        followed = move_towards(fish, board, to_board);
        if (!followed) return finish(g, Termination::max_iterations);
        follow_moved = true;
      }
      // Prey is the default of both; when both fall back to it, once is enough.
      if (!swarm_moved || !follow_moved) {
        std::optional<Fish> preyed = prey(fish);
        if (!preyed) return finish(g, Termination::max_iterations);
        (swarm_moved ? followed : swarmed) = std::move(preyed);
      }
      // Keep the behaviour with the smaller σ.
      Fish& chosen = (followed && (!swarmed || followed->f < swarmed->f)) ? *followed : *swarmed;
      swarm_[i] = std::move(chosen);
      // (5) The evaluator refreshed the bulletin board at every evaluation.
    }
    // (6)
    if (observer && !observer->on_iteration(g, eval_.evaluations(), eval_.best()))
      return finish(g, Termination::stopped);
  }
  return finish(o_.max_iterations, Termination::max_iterations);
}

}  // namespace

void IafsaEngine::Options::validate() const {
  std::map<std::string, std::string> given = {
      {"fish", fmt::format("{}", fish)},
      {"max_iterations", fmt::format("{}", max_iterations)},
      {"visual", fmt::format("{}", visual)},
      {"step", fmt::format("{}", step)},
      {"visual_min", fmt::format("{}", visual_min)},
      {"step_min", fmt::format("{}", step_min)},
      {"crowding", fmt::format("{}", crowding)},
      {"try_number", fmt::format("{}", try_number)},
      {"schedule", schedule},
  };
  OptionReader reader(kName, given);
  Options copy = *this;
  read_options(reader, copy);
  reader.finish();
  if (max_evaluations < 1)
    throw InputError(
        fmt::format("{} max_evaluations={}: must be at least 1", kName, max_evaluations));
  if (!(target_objective >= 0.0) || !std::isfinite(target_objective))
    throw InputError(fmt::format("{} target_objective={}: must be a finite number >= 0", kName,
                                 target_objective));
}

IafsaEngine::IafsaEngine(Options options) : options_(std::move(options)) { options_.validate(); }

FitResult IafsaEngine::fit(const LinearProblem& problem, FitObserver* observer) const {
  Run run(options_, problem);
  return run.go(observer);
}

EngineInfo iafsa_engine_info() {
  const IafsaEngine::Options d;
  EngineInfo info;
  info.name = kName;
  info.description =
      "improved artificial fish swarm (Yu et al. 2014): shrinking Visual and Step, swarm to the "
      "swarm's centre, follow the bulletin board";
  info.stochastic = true;
  info.default_evaluations = d.max_evaluations;
  info.options = {
      {"fish", fmt::format("{}: N, the swarm size", d.fish)},
      {"max_iterations", fmt::format("{}: G_max of eq. (5), also a stopping rule",
                                     d.max_iterations)},
      {"visual", fmt::format("{}: Visual_0, fraction of the box width", d.visual)},
      {"step", fmt::format("{}: Step_0, fraction of the box width", d.step)},
      {"visual_min", fmt::format("{}: Visual_min of eq. (5), fraction of the box width",
                                 d.visual_min)},
      {"step_min", fmt::format("{}: Step_min of eq. (5), fraction of the box width", d.step_min)},
      {"crowding", fmt::format("{}: δ, crowded when n/N ≥ δ (1: never)", d.crowding)},
      {"try_number", fmt::format("{}: prey attempts before a random step", d.try_number)},
      {"schedule", fmt::format("{}: eq. (5) as an update (compound) or from Visual_0, Step_0 "
                               "(initial)",
                               d.schedule)},
  };
  info.make = [](const EngineSettings& settings) -> std::unique_ptr<Engine> {
    IafsaEngine::Options o;
    OptionReader reader(kName, settings.options);
    read_options(reader, o);
    reader.finish();
    o.seed = settings.seed;
    if (settings.max_evaluations != 0) o.max_evaluations = settings.max_evaluations;
    o.target_objective = settings.target_objective;
    return std::make_unique<IafsaEngine>(o);
  };
  return info;
}

}  // namespace gyrotherm::fit
