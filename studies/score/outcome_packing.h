#pragma once
// Trial outcomes as bytes, for gathering them across MPI processes
// (app/score_mpi.h); doubles travel as their bytes, so unpack(pack(x)) == x
// exactly.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "studies/score/campaign.h"

namespace gyrotherm::studies {

std::string pack_outcomes(std::span<const TrialOutcome> outcomes);
std::vector<TrialOutcome> unpack_outcomes(std::string_view bytes);

}  // namespace gyrotherm::studies
