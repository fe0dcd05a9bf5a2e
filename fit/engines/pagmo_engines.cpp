#include "fit/engines/pagmo_engines.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <stdexcept>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "fit/engines/pagmo_evolve.h"
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

// The Evaluator as pagmo's fitness: the run's counting and stopping.
double fitness(RunState& run, const std::vector<double>& z) {
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
  return f;
}

// ---------------------------------------------------------------------------
// The generic engine.

// How to run one pagmo algorithm.
struct Recipe {
  std::string engine;
  std::function<long(std::size_t dimension)> population;
  long evaluations_per_individual = 1;  // per generation
  pagmo_evolve::Algorithm algorithm;
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
    RunDetail detail{.kind = RunDetail::Kind::pagmo, .population = size, .seed = settings_.seed};
    try {
      // A random initial population (evaluated through the Evaluator), then
      // evolved until the budget, the target or the observer throws StopRun,
      // or the algorithm ends by itself.
      pagmo_evolve::evolve({.algorithm = recipe_.algorithm,
                            .dimension = m,
                            .population = size,
                            .generations = generations,
                            .population_seed = population_seed,
                            .algorithm_seed = algorithm_seed,
                            .fitness = [&](const std::vector<double>& z) { return fitness(run, z); }});
      if (run.generations < static_cast<long>(generations)) {
        fallback = Termination::converged;
        detail.end = RunDetail::End::collapsed;
      } else {
        detail.end = RunDetail::End::generation_limit;
        detail.generation_limit = generations;
      }
    } catch (const StopRun&) {
      if (run.non_finite) {
        fallback = Termination::converged;
        detail.end = RunDetail::End::non_finite;
      } else if (run.observer_stopped) {
        fallback = Termination::stopped;
        detail.end = RunDetail::End::observer;
      }
    }
    return evaluator.result(recipe_.engine, run.generations, fallback, std::move(detail));
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

// Each engine below: its Options, its table (every option once: parsing and
// the listing read it), and `make`.

// ---------------------------------------------------------------------------
// pso

using pagmo_evolve::PsoOptions;

// The automatic swarm is never smaller than this (m = 1).
constexpr int kSmallestAutomaticSwarm = 12;

long spso_swarm(std::size_t m) {
  return 10 + static_cast<long>(std::floor(2.0 * std::sqrt(static_cast<double>(m))));
}

const OptionTable<PsoOptions>& pso_table() {
  using O = PsoOptions;
  static const OptionTable<O> table{"pso", {
      ruled_row<O>("population", "particles; automatic: 10 + 2 sqrt(m)",
                   &O::population, whole_or_zero(5, kMaxPopulation, "automatic")),
      ruled_row<O>("omega", "inertia weight or constriction factor", &O::omega, number_in(0.0, 1.0)),
      ruled_row<O>("eta1", "cognitive acceleration", &O::eta1, number_in(0.0, 4.0)),
      ruled_row<O>("eta2", "social acceleration", &O::eta2, number_in(0.0, 4.0)),
      ruled_row<O>("max_vel", "largest velocity as a fraction of the box", &O::max_vel, number_above(0.0, 1.0)),
      ruled_row<O>("variant", "velocity update (5 constriction, 6 fully informed)", &O::variant, whole(1, 6)),
      ruled_row<O>("topology", "1 gbest, 2 lbest ring, 3 von Neumann, 4 adaptive random",
                   &O::topology, whole(1, 4)),
      ruled_row<O>("neighbours", "lbest ring neighbours / adaptive informants, at most population - 1 (11 "
                   "with the automatic swarm)",
                   &O::neighbours, whole(2, kMaxPopulation - 1)),
  }};
  return table;
}

EngineInfo pso_info() {
  EngineInfo info = base_info("pso", "particle swarm optimisation (pagmo::pso)");
  info.options = list_options(pso_table());
  info.make = [](const EngineSettings& settings) {
    const PsoOptions o = options_from(pso_table(), settings);
    // pagmo's ring takes neighbours/2 on each side (1 would leave none) and
    // wraps once around the swarm (more than the other particles overruns it).
    const int most = (o.population > 0 ? o.population : kSmallestAutomaticSwarm) - 1;
    if (o.neighbours > most)
      reject_option("pso", "neighbours", std::to_string(o.neighbours), whole(2, most));
    Recipe recipe{
        .engine = "pso",
        .population = [o](std::size_t m) { return o.population > 0 ? o.population : spso_swarm(m); },
        .evaluations_per_individual = 1,
        .algorithm = o};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

// ---------------------------------------------------------------------------
// de

using pagmo_evolve::DeOptions;

const OptionTable<DeOptions>& de_table() {
  using O = DeOptions;
  static const OptionTable<O> table{"de", {
      ruled_row<O>("population", "individuals", &O::population, whole(5, kMaxPopulation)),
      ruled_row<O>("F", "differential weight", &O::f, number_in(0.0, 1.0)),
      ruled_row<O>("CR", "crossover probability", &O::cr, number_in(0.0, 1.0)),
      ruled_row<O>("variant", "strategy (1 best/1/exp, 2 rand/1/exp, 6 best/1/bin, 7 rand/1/bin, ...)",
                   &O::variant, whole(1, 10)),
      ruled_row<O>("ftol", "stop when the spread of sigma is below this, units of y (0: never)",
                   &O::ftol, number_in(0.0, std::numeric_limits<double>::max())),
      ruled_row<O>("xtol", "stop when best and worst differ by less in the unit box",
                   &O::xtol, number_in(0.0, 2.0)),
  }};
  return table;
}

EngineInfo de_info() {
  EngineInfo info = base_info("de", "differential evolution (pagmo::de)");
  info.options = list_options(de_table());
  info.make = [](const EngineSettings& settings) {
    const DeOptions o = options_from(de_table(), settings);
    Recipe recipe{.engine = "de",
                  .population = [o](std::size_t) { return long{o.population}; },
                  .evaluations_per_individual = 1,
                  .algorithm = o};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

// ---------------------------------------------------------------------------
// cmaes

using pagmo_evolve::CmaesOptions;

long hansen_lambda(std::size_t m) {
  // At least 5: pagmo's cmaes refuses smaller populations (m = 1 would give 4).
  return std::max(5L, 4 + static_cast<long>(std::floor(3.0 * std::log(static_cast<double>(m)))));
}

const OptionTable<CmaesOptions>& cmaes_table() {
  using O = CmaesOptions;
  static const OptionTable<O> table{"cmaes", {
      ruled_row<O>("population", "offspring per generation, lambda; automatic: 4 + 3 ln m",
                   &O::population, whole_or_zero(5, kMaxPopulation, "automatic")),
      ruled_row<O>("sigma0", "initial step as a fraction of the box width", &O::sigma0, number_above(0.0, 1.0)),
      ruled_row<O>("ftol", "stop when the spread of sigma is below this, units of y (0: never)",
                   &O::ftol, number_in(0.0, std::numeric_limits<double>::max())),
      ruled_row<O>("xtol", "stop when a step is shorter in the unit box", &O::xtol, number_in(0.0, 2.0)),
  }};
  return table;
}

EngineInfo cmaes_info() {
  EngineInfo info =
      base_info("cmaes", "covariance matrix adaptation evolution strategy (pagmo::cmaes)");
  info.options = list_options(cmaes_table());
  info.make = [](const EngineSettings& settings) {
    const CmaesOptions o = options_from(cmaes_table(), settings);
    Recipe recipe{
        .engine = "cmaes",
        .population = [o](std::size_t m) { return o.population > 0 ? o.population : hansen_lambda(m); },
        .evaluations_per_individual = 1,
        .algorithm = o};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

// ---------------------------------------------------------------------------
// abc

using pagmo_evolve::AbcOptions;

const OptionTable<AbcOptions>& abc_table() {
  using O = AbcOptions;
  static const OptionTable<O> table{"abc", {
      ruled_row<O>("population", "food sources; a generation costs twice this",
                   &O::population, whole(5, kMaxPopulation)),
      ruled_row<O>("limit", "failed trials before a source is abandoned (0: population * m)",
                   &O::limit, whole(0, 1000000)),
  }};
  return table;
}

EngineInfo abc_info() {
  EngineInfo info = base_info("abc", "artificial bee colony (pagmo::bee_colony)");
  info.options = list_options(abc_table());
  info.make = [](const EngineSettings& settings) {
    const AbcOptions o = options_from(abc_table(), settings);
    Recipe recipe{
        .engine = "abc",
        .population = [o](std::size_t) { return long{o.population}; },
        .evaluations_per_individual = 2,  // employed and onlooker phases
        .algorithm = o};
    return make_engine(std::move(recipe), settings);
  };
  return info;
}

}  // namespace

namespace pagmo_evolve {
namespace {

namespace fs = std::filesystem;

// The module's entry, loaded once (see pagmo_evolve.h for where it is looked for).
Entry load_entry() {
  std::vector<fs::path> candidates;
  const char* chosen = std::getenv("GYROTHERM_PAGMO_MODULE");
  if (chosen != nullptr && *chosen != '\0') {
    candidates.emplace_back(chosen);
  } else {
    Dl_info self{};
    if (dladdr(reinterpret_cast<const void*>(&load_entry), &self) != 0 && self.dli_fname != nullptr)
      candidates.push_back(fs::path(self.dli_fname).parent_path() / kModuleFile);
#ifdef GYROTHERM_PAGMO_MODULE_BUILT
    candidates.emplace_back(GYROTHERM_PAGMO_MODULE_BUILT);
#endif
  }
  std::string tried;
  for (const fs::path& path : candidates) {
    std::error_code ec;
    if (candidates.size() > 1 && !fs::exists(path, ec)) {
      tried += fmt::format("{}{} (absent)", tried.empty() ? "" : ", ", path.string());
      continue;
    }
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    const char* problem = module == nullptr ? dlerror() : nullptr;
    if (module != nullptr)
      if (void* entry = dlsym(module, kEntryName); entry != nullptr) return reinterpret_cast<Entry>(entry);
    tried += fmt::format("{}{} ({})", tried.empty() ? "" : ", ", path.string(),
                         problem != nullptr ? problem : "no entry " + std::string(kEntryName));
  }
  // A path the user set is their input (exit 2); a build without the module is the program's fault.
  if (chosen != nullptr && *chosen != '\0')
    throw InputError(fmt::format("GYROTHERM_PAGMO_MODULE={}: the pagmo engines (pso, de, cmaes, abc) cannot load it: "
                                 "{}; give the path of the {} the build writes, or unset it",
                                 chosen, tried, kModuleFile));
  throw std::runtime_error(fmt::format("the pagmo engines (pso, de, cmaes, abc) need the module {}, which could not "
                                       "be loaded: tried {}; build the target gyrotherm_pagmo, or set "
                                       "GYROTHERM_PAGMO_MODULE to its path",
                                       kModuleFile, tried));
}

}  // namespace

void evolve(const Run& run) {
  static const Entry entry = load_entry();
  entry(run);
}

}  // namespace pagmo_evolve

std::vector<EngineInfo> pagmo_engine_infos() {
  return {pso_info(), de_info(), cmaes_info(), abc_info()};
}

}  // namespace gyrotherm::fit
