#include "fit/afsa.h"

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

constexpr char kName[] = "afsa";
// The engine's stream of make_rng(seed, stream).
constexpr std::uint64_t kStream = 0xAF5A;
constexpr double kBoxWidth = 2.0;

// The one place the option rules live: make() reads KEY=VALUE strings with
// them and validate() checks an Options aggregate with the same reader.
void read_options(OptionReader& reader, AfsaEngine::Options& o) {
  reader.integer("fish", o.fish, 2, 100000);
  reader.integer("max_iterations", o.max_iterations, 1, 100000000);
  reader.real("visual", o.visual, 0.0, 1.0, true);
  reader.real("step", o.step, 0.0, 1.0, true);
  reader.real("crowding", o.crowding, 0.0, 1.0, true);
  reader.integer("try_number", o.try_number, 1, 1000);
}

struct Fish {
  std::vector<double> x;
  double f = 0.0;
};

// One run: the swarm, the generator and the evaluator (whose best point is
// the bulletin board). evaluate() refuses once the budget is spent or the
// target reached; a behaviour that meets a refusal returns nullopt and the
// run unwinds.
class Run {
 public:
  Run(const AfsaEngine::Options& o, const LinearProblem& problem)
      : o_(o),
        eval_(problem, o.max_evaluations, o.target_objective),
        rng_(sim::make_rng(o.seed, kStream)),
        m_(problem.dimension()),
        visual_(o.visual * kBoxWidth),
        step_(o.step * kBoxWidth) {}

  FitResult go(FitObserver* observer);

 private:
  std::optional<double> evaluate(std::vector<double>& x) {
    if (eval_.done()) return std::nullopt;
    for (double& v : x) v = std::clamp(v, -1.0, 1.0);
    return eval_(x);
  }

  // X_i + Rand()·Step·(target − X_i)/‖target − X_i‖, eqs. (1), (3), (4).
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

  // (1) Prey.
  std::optional<Fish> prey(const Fish& fish) {
    std::vector<double> probe(m_);
    for (int t = 0; t < o_.try_number; ++t) {
      for (std::size_t k = 0; k < m_; ++k) probe[k] = fish.x[k] + visual_ * unit_(rng_);
      const std::optional<double> f = evaluate(probe);
      if (!f) return std::nullopt;
      const double d = distance(probe, fish.x);
      if (*f < fish.f && d > 0.0) return move_towards(fish, probe, d);
    }
    Fish next{fish.x, 0.0};
    for (std::size_t k = 0; k < m_; ++k) next.x[k] += step_ * unit_(rng_);
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

  const AfsaEngine::Options& o_;
  Evaluator eval_;
  sim::Rng rng_;
  boost::random::uniform_real_distribution<double> unit_{-1.0, 1.0};
  boost::random::uniform_real_distribution<double> rand01_{0.0, 1.0};
  std::size_t m_;
  double visual_;  // in box coordinates (the width is 2)
  double step_;
  std::vector<Fish> swarm_;
};

FitResult Run::go(FitObserver* observer) {
  const std::size_t n = static_cast<std::size_t>(o_.fish);
  const auto finish = [&](long iterations, Termination fallback) {
    return eval_.result(kName, iterations, fallback,
                        fmt::format("{} fish, {} of {} iterations; Visual {:.3g}, Step {:.3g} "
                                    "(box widths)",
                                    n, iterations, o_.max_iterations, o_.visual, o_.step));
  };

  // Scatter the swarm over the box; the evaluator's best point is the
  // bulletin board from the first evaluation on.
  swarm_.assign(n, Fish{std::vector<double>(m_, 0.0), 0.0});
  for (Fish& fish : swarm_) {
    for (double& v : fish.x) v = unit_(rng_);
    const std::optional<double> f = evaluate(fish.x);
    if (!f) return finish(0, Termination::max_iterations);
    fish.f = *f;
  }

  std::vector<double> centre(m_);
  for (long g = 1; g <= o_.max_iterations; ++g) {
    for (std::size_t i = 0; i < n; ++i) {
      const Fish& fish = swarm_[i];
      // The mates within Visual: their number, centre and best.
      int n_f = 0;
      std::size_t best = i;
      std::fill(centre.begin(), centre.end(), 0.0);
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i || distance(swarm_[j].x, fish.x) >= visual_) continue;
        ++n_f;
        for (std::size_t k = 0; k < m_; ++k) centre[k] += swarm_[j].x[k];
        if (best == i || swarm_[j].f < swarm_[best].f) best = j;
      }
      const bool uncrowded =
          n_f >= 1 && static_cast<double>(n_f) / static_cast<double>(n) < o_.crowding;

      // (2) Swarm.
      std::optional<Fish> swarmed;
      bool swarm_moved = false;
      if (uncrowded) {
        for (double& c : centre) c /= static_cast<double>(n_f);
        const std::optional<double> f_centre = evaluate(centre);
        if (!f_centre) return finish(g, Termination::max_iterations);
        const double to_centre = distance(fish.x, centre);
        if (*f_centre < fish.f && to_centre > 0.0) {
          swarmed = move_towards(fish, centre, to_centre);
          if (!swarmed) return finish(g, Termination::max_iterations);
          swarm_moved = true;
        }
      }
      // (3) Follow.
      std::optional<Fish> followed;
      bool follow_moved = false;
      if (uncrowded && swarm_[best].f < fish.f) {
        const std::vector<double> leader = swarm_[best].x;
        followed = move_towards(fish, leader, distance(fish.x, leader));
        if (!followed) return finish(g, Termination::max_iterations);
        follow_moved = true;
      }
      // (1) Prey stands in for a move whose test failed; once serves both.
      if (!swarm_moved || !follow_moved) {
        std::optional<Fish> preyed = prey(fish);
        if (!preyed) return finish(g, Termination::max_iterations);
        (swarm_moved ? followed : swarmed) = std::move(preyed);
      }
      // Take the better of the two moves.
      Fish& chosen = (followed && (!swarmed || followed->f < swarmed->f)) ? *followed : *swarmed;
      swarm_[i] = std::move(chosen);
    }
    if (observer && !observer->on_iteration(g, eval_.evaluations(), eval_.best()))
      return finish(g, Termination::stopped);
  }
  return finish(o_.max_iterations, Termination::max_iterations);
}

}  // namespace

void AfsaEngine::Options::validate() const {
  std::map<std::string, std::string> given = {
      {"fish", fmt::format("{}", fish)},
      {"max_iterations", fmt::format("{}", max_iterations)},
      {"visual", fmt::format("{}", visual)},
      {"step", fmt::format("{}", step)},
      {"crowding", fmt::format("{}", crowding)},
      {"try_number", fmt::format("{}", try_number)},
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

AfsaEngine::AfsaEngine(Options options) : options_(std::move(options)) { options_.validate(); }

FitResult AfsaEngine::fit(const LinearProblem& problem, FitObserver* observer) const {
  Run run(options_, problem);
  return run.go(observer);
}

EngineInfo afsa_engine_info() {
  const AfsaEngine::Options d;
  EngineInfo info;
  info.name = kName;
  info.description =
      "artificial fish swarm (Li 2002): prey, swarm and follow within a fixed Visual and Step";
  info.stochastic = true;
  info.default_evaluations = d.max_evaluations;
  info.options = {
      {"fish", fmt::format("{}: N, the swarm size", d.fish)},
      {"max_iterations", fmt::format("{}: iteration limit", d.max_iterations)},
      {"visual", fmt::format("{}: Visual, fraction of the box width", d.visual)},
      {"step", fmt::format("{}: Step, fraction of the box width", d.step)},
      {"crowding", fmt::format("{}: δ, crowded when n_f/N ≥ δ (1: never)", d.crowding)},
      {"try_number", fmt::format("{}: prey attempts before a random step", d.try_number)},
  };
  info.make = [](const EngineSettings& settings) -> std::unique_ptr<Engine> {
    AfsaEngine::Options o;
    OptionReader reader(kName, settings.options);
    read_options(reader, o);
    reader.finish();
    o.seed = settings.seed;
    if (settings.max_evaluations != 0) o.max_evaluations = settings.max_evaluations;
    o.target_objective = settings.target_objective;
    return std::make_unique<AfsaEngine>(o);
  };
  return info;
}

}  // namespace gyrotherm::fit
