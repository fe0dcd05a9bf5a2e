#pragma once
// The one call from the pagmo engines (pagmo_engines.cpp) into libpagmo. It
// lives in a module of its own, libgyrotherm_pagmo.so (fit/engines/pagmo/),
// loaded at the first pagmo fit: libpagmo's static initialisers (its test
// problems' tables) cost about 60 ms at every start of a program linked to
// it — most of a command's start — whether or not it ever runs pagmo.
//
// The module is found, in this order, at GYROTHERM_PAGMO_MODULE (a path, when
// set: then nowhere else), beside the program or library that holds this
// code (an installed Python package has it beside its extension), and where
// the build put it.

#include <cstddef>
#include <functional>
#include <variant>
#include <vector>

namespace gyrotherm::fit::pagmo_evolve {

// Each algorithm's settings (the engines' options, pagmo_engines.h).
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
struct DeOptions {
  int population = 20;  // individuals
  double f = 0.8;       // F, differential weight
  double cr = 0.9;      // CR, crossover probability
  int variant = 2;      // pagmo's mutation/crossover 1..10 (2: rand/1/exp)
  double ftol = 0.0;    // stop when the population's σ spread is below (0: never)
  double xtol = 1e-12;  // stop when best and worst differ by less (L1, unit box)
};
struct CmaesOptions {
  int population = 0;   // λ (0: 4 + ⌊3 ln m⌋, Hansen's default)
  double sigma0 = 0.5;  // initial step, as a fraction of the box width
  double ftol = 0.0;    // stop when the population's σ spread is below (0: never)
  double xtol = 1e-12;  // stop when a step is shorter (unit box)
};
struct AbcOptions {
  int population = 20;  // food sources (employed bees = onlooker bees)
  int limit = 0;        // failed trials before a source is abandoned (0: population·m)
};
using Algorithm = std::variant<PsoOptions, DeOptions, CmaesOptions, AbcOptions>;

struct Run {
  Algorithm algorithm;
  std::size_t dimension = 0;  // m: the unit box [−1, 1]^m
  long population = 0;        // resolved for m
  unsigned generations = 0;   // enough to spend the budget
  unsigned population_seed = 0, algorithm_seed = 0;
  // σ at z; throws to end the run (the exception passes through pagmo's
  // frames to the caller of evolve).
  std::function<double(const std::vector<double>& z)> fitness;
};

// A random population of run.population in the box, then the algorithm
// evolved for run.generations. Throws std::runtime_error naming the module
// when it cannot be loaded.
void evolve(const Run& run);

// The module's entry: extern "C", found by dlsym.
using Entry = void (*)(const Run& run);
inline constexpr const char* kEntryName = "gyrotherm_pagmo_evolve";
inline constexpr const char* kModuleFile = "libgyrotherm_pagmo.so";

}  // namespace gyrotherm::fit::pagmo_evolve
