#pragma once
// MPI for `gyrotherm score`, and only for it: every MPI call of the program is
// in score_mpi.cpp. Built with GYROTHERM_WITH_MPI (CMake option, on when MPI
// is found); without it, or when not started by mpirun, this is one process
// of rank 0 and gather() returns its own bytes.
//
//   mpirun -np K gyrotherm score ...   rank r runs trials k ≡ r (mod K); the
//                                      outcomes are gathered on rank 0, which
//                                      alone prints and writes files.
//
// MPI_Init is called only when the process was started by an MPI launcher
// (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in the environment), so every
// other command, and score run by hand, never touches MPI.

#include <string>
#include <vector>

namespace gyrotherm::app {

class ScoreMpi {
 public:
  // Initialises MPI (threads: funnelled) if started by mpirun. Throws
  // InputError if started by mpirun with several ranks but built without MPI.
  ScoreMpi();
  ~ScoreMpi();  // MPI_Finalize if this object initialised MPI
  ScoreMpi(const ScoreMpi&) = delete;
  ScoreMpi& operator=(const ScoreMpi&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // Rank 0 receives every rank's bytes, in rank order; the others get nothing.
  std::vector<std::string> gather(const std::string& bytes) const;
  // Rank 0's value, on every rank.
  int broadcast(int value) const;

  static bool built_with_mpi();
  // Started by an MPI launcher (the environment says so).
  static bool launched_by_mpirun();
  // The rank the launcher assigned (from the environment; 0 when none).
  static int launcher_rank();

 private:
  int rank_ = 0;
  int size_ = 1;
  bool initialised_ = false;
};

}  // namespace gyrotherm::app
