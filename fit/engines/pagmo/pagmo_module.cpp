// libgyrotherm_pagmo.so: the pagmo engines' one call into libpagmo
// (fit/engines/pagmo_evolve.h), a module loaded at the first pagmo fit. It
// uses nothing of gyrotherm's libraries: the fitness is the caller's function.
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
#error "fit/engines/pagmo/pagmo_module.cpp must use Eigen's malloc-aligned 16-byte storage, as libpagmo does: build it without -march=native/-mavx; under AddressSanitizer add -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
#endif

#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <variant>

#include "fit/engines/pagmo_evolve.h"

namespace gyrotherm::fit::pagmo_evolve {
namespace {

// A pagmo problem whose fitness is the run's.
class FitnessProblem {
 public:
  FitnessProblem() = default;  // pagmo requires it (serialisation)
  explicit FitnessProblem(const Run* run) : run_(run) {}

  pagmo::vector_double fitness(const pagmo::vector_double& z) const { return {run_->fitness(z)}; }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    const std::size_t m = run_ != nullptr ? run_->dimension : 1;
    return {pagmo::vector_double(m, -1.0), pagmo::vector_double(m, 1.0)};
  }
  // The caller's fitness is not safe to call from several threads.
  pagmo::thread_safety get_thread_safety() const { return pagmo::thread_safety::none; }
  std::string get_name() const { return "gyrotherm sigma(z) on the unit box"; }

 private:
  const Run* run_ = nullptr;
};

unsigned whole(long v) {
  return static_cast<unsigned>(std::clamp<long>(v, 0, std::numeric_limits<unsigned>::max()));
}

pagmo::algorithm algorithm_of(const Run& run) {
  const unsigned g = run.generations, seed = run.algorithm_seed;
  return std::visit(
      [&](const auto& o) -> pagmo::algorithm {
        using O = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<O, PsoOptions>) {
          return pagmo::algorithm(pagmo::pso(g, o.omega, o.eta1, o.eta2, o.max_vel, whole(o.variant),
                                             whole(o.topology), whole(o.neighbours), /*memory=*/false, seed));
        } else if constexpr (std::is_same_v<O, DeOptions>) {
          return pagmo::algorithm(pagmo::de(g, o.f, o.cr, whole(o.variant), o.ftol, o.xtol, seed));
        } else if constexpr (std::is_same_v<O, CmaesOptions>) {
          // cc, cs, c1, cmu = -1: Hansen's settings for λ and m. force_bounds
          // on: the fitness clamps into the box, so CMA-ES must not learn
          // from points it did not evaluate.
          return pagmo::algorithm(pagmo::cmaes(g, -1, -1, -1, -1, o.sigma0, o.ftol, o.xtol, /*memory=*/false,
                                               /*force_bounds=*/true, seed));
        } else {
          // Karaboga & Basturk's limit = SN·D (food sources × dimension).
          const long limit = o.limit > 0 ? o.limit : run.population * static_cast<long>(run.dimension);
          return pagmo::algorithm(pagmo::bee_colony(g, whole(limit), seed));
        }
      },
      run.algorithm);
}

}  // namespace
}  // namespace gyrotherm::fit::pagmo_evolve

extern "C" [[gnu::visibility("default")]] void gyrotherm_pagmo_evolve(
    const gyrotherm::fit::pagmo_evolve::Run& run) {
  using namespace gyrotherm::fit::pagmo_evolve;
  pagmo::population population(FitnessProblem(&run), static_cast<pagmo::population::size_type>(run.population),
                               run.population_seed);
  const pagmo::algorithm algorithm = algorithm_of(run);
  population = algorithm.evolve(population);
}
