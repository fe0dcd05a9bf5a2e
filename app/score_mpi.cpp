// The only translation unit that calls MPI (app/score_mpi.h).

#include "app/score_mpi.h"

#include <fmt/format.h>

#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "sim/util/input_error.h"

#ifdef GYROTHERM_WITH_MPI
#include <mpi.h>
#endif

namespace gyrotherm::app {
namespace {

const char* env(const char* name) { return std::getenv(name); }

int env_int(const char* name, int fallback) {
  const char* v = env(name);
  return v != nullptr && *v != '\0' ? std::atoi(v) : fallback;
}

#ifdef GYROTHERM_WITH_MPI
void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(fmt::format("MPI: {} failed (code {})", what, code));
}
#endif

}  // namespace

bool ScoreMpi::built_with_mpi() {
#ifdef GYROTHERM_WITH_MPI
  return true;
#else
  return false;
#endif
}

bool ScoreMpi::launched_by_mpirun() {
  return env("OMPI_COMM_WORLD_SIZE") != nullptr || env("PMI_SIZE") != nullptr ||
         env("PMIX_RANK") != nullptr;
}

int ScoreMpi::launcher_rank() {
  return env_int("OMPI_COMM_WORLD_RANK", env_int("PMI_RANK", env_int("PMIX_RANK", 0)));
}

ScoreMpi::ScoreMpi() {
  if (!launched_by_mpirun()) return;
#ifdef GYROTHERM_WITH_MPI
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  initialised_ = true;
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
#else
  const int size = env_int("OMPI_COMM_WORLD_SIZE", env_int("PMI_SIZE", 1));
  if (size > 1)
    throw InputError(fmt::format(
        "started by mpirun with {} ranks, but this gyrotherm was built without MPI "
        "(GYROTHERM_WITH_MPI=OFF): every rank would run the whole campaign; run it without "
        "mpirun, or build with MPI",
        size));
#endif
}

ScoreMpi::~ScoreMpi() {
#ifdef GYROTHERM_WITH_MPI
  if (initialised_) MPI_Finalize();
#endif
}

std::vector<std::string> ScoreMpi::gather(const std::string& bytes) const {
#ifdef GYROTHERM_WITH_MPI
  if (initialised_ && size_ > 1) {
    // 1. Every rank's byte count to rank 0; 2. the bytes themselves.
    if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::runtime_error("MPI: a rank's trial outcomes exceed 2 GiB; use fewer trials per rank");
    const int count = static_cast<int>(bytes.size());
    std::vector<int> counts(root() ? static_cast<std::size_t>(size_) : 0);
    check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
    std::vector<int> displacements(counts.size());
    long long total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      displacements[r] = static_cast<int>(total);
      total += counts[r];
    }
    if (total > std::numeric_limits<int>::max())
      throw std::runtime_error("MPI: the gathered trial outcomes exceed 2 GiB; use fewer trials");
    std::string all(static_cast<std::size_t>(total), '\0');
    check(MPI_Gatherv(bytes.data(), count, MPI_CHAR, all.data(), counts.data(), displacements.data(),
                      MPI_CHAR, 0, MPI_COMM_WORLD),
          "MPI_Gatherv");
    std::vector<std::string> out;
    for (std::size_t r = 0; r < counts.size(); ++r)
      out.push_back(all.substr(static_cast<std::size_t>(displacements[r]), static_cast<std::size_t>(counts[r])));
    return out;
  }
#endif
  return {bytes};
}

int ScoreMpi::broadcast(int value) const {
#ifdef GYROTHERM_WITH_MPI
  if (initialised_ && size_ > 1) check(MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
#endif
  return value;
}

}  // namespace gyrotherm::app
