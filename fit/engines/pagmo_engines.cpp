#include "fit/engines/pagmo_engines.h"

#include <fmt/format.h>

#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/bee_colony.hpp>
#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/pso.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/threading.hpp>
#include <pagmo/types.hpp>

// pagmo::cmaes holds Eigen matrices that libpagmo allocates and this file
// frees (its destructor is inline), so Eigen must allocate here as it did
// when libpagmo was built: plain malloc, 16-byte alignment. Otherwise the
// first cmaes run corrupts the heap.
#if !EIGEN_MALLOC_ALREADY_ALIGNED || EIGEN_DEFAULT_ALIGN_BYTES > 16
#error "fit/engines/pagmo_engines.cpp must use Eigen's malloc-aligned 16-byte storage, as libpagmo does: build it without -march=native/-mavx; under AddressSanitizer add -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
#endif

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "sim/util/input_error.h"
#include "sim/util/random.h"

namespace gyrotherm::fit {
namespace {

// ---------------------------------------------------------------------------
// The adapter: a pagmo problem whose fitness is the Evaluator.

// What one run shares between the engine and the copies pagmo makes of the
// problem (the population and evolve() each copy it).
struct RunState {
  Evaluator* evaluator = nullptr;
  FitObserver* observer = nullptr;
  long initial = 0;         // evaluations of the initial population
  long per_generation = 1;  // evaluations of one generation
  long generations = 0;     // completed generations
  bool observer_stopped = false;
  bool non_finite = false;  // the algorithm proposed a NaN/inf coordinate
};

// Thrown through pagmo to end the run; not a std::exception, so nothing that
// catches those can swallow it.
struct StopRun {};

class EvaluatorProblem {
 public:
  EvaluatorProblem() = default;  // pagmo requires it (serialisation)
  EvaluatorProblem(RunState* run, std::size_t dimension) : run_(run), dimension_(dimension) {}

  pagmo::vector_double fitness(const pagmo::vector_double& z) const {
    assert(run_ != nullptr && z.size() == dimension_);
    RunState& run = *run_;
    Evaluator& evaluator = *run.evaluator;
    // Never evaluate past the budget or the target (the throw below normally
    // ends the run first; this guards a second call).
    if (evaluator.done()) throw StopRun{};
    // σ of a NaN point would read as 0 (std::max(0, NaN) in the Gram form)
    // and become the best; stop instead.
    if (!std::all_of(z.begin(), z.end(), [](double v) { return std::isfinite(v); })) {
      run.non_finite = true;
      throw StopRun{};
    }
    const double f = evaluator(z);
    const long since_start = evaluator.evaluations() - run.initial;
    if (since_start > 0 && since_start % run.per_generation == 0) {
      ++run.generations;
      if (run.observer != nullptr &&
          !run.observer->on_iteration(run.generations, evaluator.evaluations(), evaluator.best())) {
        run.observer_stopped = true;
        throw StopRun{};
      }
    }
    if (evaluator.done()) throw StopRun{};
    return {f};
  }

  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {pagmo::vector_double(dimension_, -1.0), pagmo::vector_double(dimension_, 1.0)};
  }
  // The run state is not shared safely between threads.
  pagmo::thread_safety get_thread_safety() const { return pagmo::thread_safety::none; }
  std::string get_name() const { return "gyrotherm sigma(z) on the unit box"; }

 private:
  RunState* run_ = nullptr;
  std::size_t dimension_ = 1;
};

// ---------------------------------------------------------------------------
// The generic engine.

// What a recipe needs to build its algorithm for one run.
struct RunPlan {
  std::size_t dimension = 0;  // m
  long population = 0;        // resolved for m
  unsigned generations = 0;   // enough to spend the budget
  unsigned seed = 0;          // the algorithm's own
};

// How to run one pagmo algorithm.
struct Recipe {
  std::string engine;
  std::function<long(std::size_t dimension)> population;
  long evaluations_per_individual = 1;  // per generation
  std::function<pagmo::algorithm(const RunPlan&)> make_algorithm;
};

class PagmoEngine final : public Engine {
 public:
  PagmoEngine(Recipe recipe, EngineSettings settings)
      : recipe_(std::move(recipe)), settings_(std::move(settings)) {}

  FitResult fit(const LinearProblem& problem, FitObserver* observer) const override {
    const std::size_t m = problem.dimension();
    const long budget =
        settings_.max_evaluations > 0 ? settings_.max_evaluations : kPagmoDefaultEvaluations;
    const long size = recipe_.population(m);
    const long per_generation = recipe_.evaluations_per_individual * size;

    // Two decorrelated seeds from the one user seed (the SplitMix64 sequence).
    std::uint64_t state = settings_.seed;
    const auto population_seed = static_cast<unsigned>(splitmix64_next(state) >> 32);
    const auto algorithm_seed = static_cast<unsigned>(splitmix64_next(state) >> 32);

    // Enough generations to spend the whole budget; the last may be cut short.
    const long affordable = budget > size ? (budget - size + per_generation - 1) / per_generation : 0;
    const auto generations = static_cast<unsigned>(
        std::min<long>(affordable, std::numeric_limits<unsigned>::max()));

    Evaluator evaluator(problem, budget, settings_.target_objective);
    RunState run{.evaluator = &evaluator,
                 .observer = observer,
                 .initial = size,
                 .per_generation = per_generation};
    Termination fallback = Termination::max_iterations;
    std::string why;
    try {
      // 1. Random initial population (evaluated through the Evaluator).
      pagmo::population population(EvaluatorProblem(&run, m),
                                   static_cast<pagmo::population::size_type>(size), population_seed);
      // 2. Evolve until the budget, the target or the observer throws StopRun,
      //    or the algorithm ends by itself.
      const pagmo::algorithm algorithm = recipe_.make_algorithm(
          {.dimension = m, .population = size, .generations = generations, .seed = algorithm_seed});
      population = algorithm.evolve(population);
      if (run.generations < static_cast<long>(generations)) {
        fallback = Termination::converged;
        why = "population collapsed (xtol/ftol)";
      } else {
        why = fmt::format("generation limit {}", generations);
      }
    } catch (const StopRun&) {
      if (run.non_finite) {
        fallback = Termination::converged;
        why = "the algorithm proposed a non-finite point (step size underflow)";
      } else if (run.observer_stopped) {
        fallback = Termination::stopped;
        why = "stopped by the observer";
      }
    }
    std::string message = fmt::format("pagmo {}, population {}, seed {}", recipe_.engine, size,
                                      settings_.seed);
    if (!why.empty()) message += "; " + why;
    return evaluator.result(recipe_.engine, run.generations, fallback, std::move(message));
  }

 private:
  Recipe recipe_;
  EngineSettings settings_;
};

// Checks the settings every pagmo engine shares and makes the engine.
std::unique_ptr<Engine> make_engine(Recipe recipe, const EngineSettings& settings) {
  if (settings.max_evaluations < 0)
    throw InputError(fmt::format("{}: max_evaluations={}: must be >= 0 (0: {})", recipe.engine,
                                 settings.max_evaluations, kPagmoDefaultEvaluations));
  if (!(settings.target_objective >= 0.0) || !std::isfinite(settings.target_objective))
    throw InputError(fmt::format("{}: target_objective={}: must be a finite number >= 0 (0: none)",
                                 recipe.engine, settings.target_objective));
  return std::make_unique<PagmoEngine>(std::move(recipe), settings);
}

constexpr int kMaxPopulation = 100000;

EngineInfo base_info(std::string name, std::string description) {
  EngineInfo info;
  info.name = std::move(name);
  info.description = std::move(description);
  info.stochastic = true;
  info.default_evaluations = kPagmoDefaultEvaluations;
  return info;
}

// Reads `population`: 0 (automatic, when `automatic` says how) or 5..kMaxPopulation;
// pagmo's de and cmaes need at least 5 individuals.
void read_population(OptionReader& reader, const std::string& engine,
                     const std::map<std::string, std::string>& options, int& value, bool automatic) {
  reader.integer("population", value, automatic ? 0 : 5, kMaxPopulation);
  if (automatic && value > 0 && value < 5)
    throw InputError(fmt::format("{} option population={}: must be 0 (automatic) or a whole number "
                                 "from 5 to {}",
                                 engine, options.at("population"), kMaxPopulation));
}

// ---------------------------------------------------------------------------
// pso

struct PsoOptions {
  int population = 0;     // particles (0: 10 + ⌊2√m⌋, SPSO 2007)
  double omega = 0.7298;  // inertia weight, or constriction factor (variants 5, 6)
  double eta1 = 2.05;     // cognitive (own best) acceleration
  double eta2 = 2.05;     // social (neighbours' best) acceleration
  double max_vel = 0.5;   // largest velocity, as a fraction of the box width
  int variant = 5;        // pagmo's velocity update 1..6 (5: constriction)
  int topology = 2;       // 1 gbest, 2 lbest ring, 3 von Neumann, 4 adaptive random
  int neighbours = 4;     // lbest: neighbours in the ring; adaptive: informants
};

// The automatic swarm is never smaller than this (m = 1).
constexpr int kSmallestAutomaticSwarm = 12;

long spso_swarm(std::size_t m) {
  return 10 + static_cast<long>(std::floor(2.0 * std::sqrt(static_cast<double>(m))));
}

EngineInfo pso_info() {
  const PsoOptions d;
  EngineInfo info = base_info("pso", "particle swarm optimisation (pagmo::pso)");
  info.options = {
      {"population", fmt::format("{}: particles (0: 10 + 2 sqrt(m); else 5..{})", d.population,
                                 kMaxPopulation)},
      {"omega", fmt::format("{}: inertia weight or constriction factor (0..1)", d.omega)},
      {"eta1", fmt::format("{}: cognitive acceleration (0..4)", d.eta1)},
      {"eta2", fmt::format("{}: social acceleration (0..4)", d.eta2)},
      {"max_vel", fmt::format("{}: largest velocity as a fraction of the box (>0..1)", d.max_vel)},
      {"variant", fmt::format("{}: velocity update 1..6 (5 constriction, 6 fully informed)", d.variant)},
      {"topology", fmt::format("{}: 1 gbest, 2 lbest ring, 3 von Neumann, 4 adaptive random",
                               d.topology)},
      {"neighbours", fmt::format("{}: lbest ring neighbours / adaptive informants (2..population-1; "
                                 "2..{} with the automatic swarm)",
                                 d.neighbours, kSmallestAutomaticSwarm - 1)},
  };
  info.make = [](const EngineSettings& settings) {
    PsoOptions o;
    OptionReader r("pso", settings.options);
    read_population(r, "pso", settings.options, o.population, /*automatic=*/true);
    r.real("omega", o.omega, 0.0, 1.0);
    r.real("eta1", o.eta1, 0.0, 4.0);
    r.real("eta2", o.eta2, 0.0, 4.0);
    r.real("max_vel", o.max_vel, 0.0, 1.0, /*lo_open=*/true);
    r.integer("variant", o.variant, 1, 6);
    r.integer("topology", o.topology, 1, 4);
    // pagmo's ring takes neighbours/2 on each side (1 would leave none) and
    // wraps once around the swarm (more than the other particles overruns it).
    r.integer("neighbours", o.neighbours, 2,
              (o.population > 0 ? o.population : kSmallestAutomaticSwarm) - 1);
    r.finish();
    Recipe recipe{
        .engine = "pso",
        .population = [o](std::size_t m) { return o.population > 0 ? o.population : spso_swarm(m); },
        .evaluations_per_individual = 1,
        .make_algorithm = [o](const RunPlan& plan) {
          return pagmo::algorithm(pagmo::pso(plan.generations, o.omega, o.eta1, o.eta2, o.max_vel,
                                             static_cast<unsigned>(o.variant),
                                             static_cast<unsigned>(o.topology),
                                             static_cast<unsigned>(o.neighbours),
                                             /*memory=*/false, plan.seed));
        }};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

// ---------------------------------------------------------------------------
// de

struct DeOptions {
  int population = 20;  // individuals
  double f = 0.8;       // F, differential weight
  double cr = 0.9;      // CR, crossover probability
  int variant = 2;      // pagmo's mutation/crossover 1..10 (2: rand/1/exp)
  double ftol = 0.0;    // stop when the population's σ spread is below (0: never)
  double xtol = 1e-12;  // stop when best and worst differ by less (L1, unit box)
};

EngineInfo de_info() {
  const DeOptions d;
  EngineInfo info = base_info("de", "differential evolution (pagmo::de)");
  info.options = {
      {"population", fmt::format("{}: individuals (5..{})", d.population, kMaxPopulation)},
      {"F", fmt::format("{}: differential weight (0..1)", d.f)},
      {"CR", fmt::format("{}: crossover probability (0..1)", d.cr)},
      {"variant", fmt::format("{}: strategy 1..10 (1 best/1/exp, 2 rand/1/exp, 6 best/1/bin, "
                              "7 rand/1/bin, ...)",
                              d.variant)},
      {"ftol", fmt::format("{}: stop when the spread of sigma is below this, units of y (0: never)",
                           d.ftol)},
      {"xtol", fmt::format("{}: stop when best and worst differ by less in the unit box (0..2)",
                           d.xtol)},
  };
  info.make = [](const EngineSettings& settings) {
    DeOptions o;
    OptionReader r("de", settings.options);
    read_population(r, "de", settings.options, o.population, /*automatic=*/false);
    r.real("F", o.f, 0.0, 1.0);
    r.real("CR", o.cr, 0.0, 1.0);
    r.integer("variant", o.variant, 1, 10);
    r.real("ftol", o.ftol, 0.0, std::numeric_limits<double>::max());
    r.real("xtol", o.xtol, 0.0, 2.0);
    r.finish();
    Recipe recipe{.engine = "de",
                  .population = [o](std::size_t) { return long{o.population}; },
                  .evaluations_per_individual = 1,
                  .make_algorithm = [o](const RunPlan& plan) {
                    return pagmo::algorithm(pagmo::de(plan.generations, o.f, o.cr,
                                                      static_cast<unsigned>(o.variant), o.ftol,
                                                      o.xtol, plan.seed));
                  }};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

// ---------------------------------------------------------------------------
// cmaes

struct CmaesOptions {
  int population = 0;   // λ (0: 4 + ⌊3 ln m⌋, Hansen's default)
  double sigma0 = 0.5;  // initial step, as a fraction of the box width
  double ftol = 0.0;    // stop when the population's σ spread is below (0: never)
  double xtol = 1e-12;  // stop when a step is shorter (unit box)
};

long hansen_lambda(std::size_t m) {
  // At least 5: pagmo's cmaes refuses smaller populations (m = 1 would give 4).
  return std::max(5L, 4 + static_cast<long>(std::floor(3.0 * std::log(static_cast<double>(m)))));
}

EngineInfo cmaes_info() {
  const CmaesOptions d;
  EngineInfo info =
      base_info("cmaes", "covariance matrix adaptation evolution strategy (pagmo::cmaes)");
  info.options = {
      {"population", fmt::format("{}: offspring per generation, lambda (0: 4 + 3 ln m; else 5..{})",
                                 d.population, kMaxPopulation)},
      {"sigma0", fmt::format("{}: initial step as a fraction of the box width (>0..1)", d.sigma0)},
      {"ftol", fmt::format("{}: stop when the spread of sigma is below this, units of y (0: never)",
                           d.ftol)},
      {"xtol", fmt::format("{}: stop when a step is shorter in the unit box (0..2)", d.xtol)},
  };
  info.make = [](const EngineSettings& settings) {
    CmaesOptions o;
    OptionReader r("cmaes", settings.options);
    read_population(r, "cmaes", settings.options, o.population, /*automatic=*/true);
    r.real("sigma0", o.sigma0, 0.0, 1.0, /*lo_open=*/true);
    r.real("ftol", o.ftol, 0.0, std::numeric_limits<double>::max());
    r.real("xtol", o.xtol, 0.0, 2.0);
    r.finish();
    Recipe recipe{
        .engine = "cmaes",
        .population = [o](std::size_t m) { return o.population > 0 ? o.population : hansen_lambda(m); },
        .evaluations_per_individual = 1,
        .make_algorithm = [o](const RunPlan& plan) {
          // cc, cs, c1, cmu = -1: Hansen's settings for λ and m.
          return pagmo::algorithm(pagmo::cmaes(plan.generations, -1, -1, -1, -1, o.sigma0, o.ftol,
                                               o.xtol, /*memory=*/false, /*force_bounds=*/true,
                                               plan.seed));
        }};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

// ---------------------------------------------------------------------------
// abc

struct AbcOptions {
  int population = 20;  // food sources (employed bees = onlooker bees)
  int limit = 0;        // failed trials before a source is abandoned (0: population·m)
};

EngineInfo abc_info() {
  const AbcOptions d;
  EngineInfo info = base_info("abc", "artificial bee colony (pagmo::bee_colony)");
  info.options = {
      {"population", fmt::format("{}: food sources; a generation costs twice this (5..{})",
                                 d.population, kMaxPopulation)},
      {"limit", fmt::format("{}: failed trials before a source is abandoned (0: population * m; "
                            "else 1..1000000)",
                            d.limit)},
  };
  info.make = [](const EngineSettings& settings) {
    AbcOptions o;
    OptionReader r("abc", settings.options);
    read_population(r, "abc", settings.options, o.population, /*automatic=*/false);
    r.integer("limit", o.limit, 0, 1000000);
    r.finish();
    Recipe recipe{
        .engine = "abc",
        .population = [o](std::size_t) { return long{o.population}; },
        .evaluations_per_individual = 2,  // employed and onlooker phases
        .make_algorithm = [o](const RunPlan& plan) {
          // Karaboga & Basturk's limit = SN·D (food sources × dimension).
          const long limit = o.limit > 0 ? o.limit : plan.population * static_cast<long>(plan.dimension);
          return pagmo::algorithm(pagmo::bee_colony(
              plan.generations,
              static_cast<unsigned>(std::min<long>(limit, std::numeric_limits<unsigned>::max())),
              plan.seed));
        }};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

}  // namespace

std::vector<EngineInfo> pagmo_engine_infos() {
  return {pso_info(), de_info(), cmaes_info(), abc_info()};
}

}  // namespace gyrotherm::fit
