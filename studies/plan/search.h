#pragma once
// The shortest profile that meets the precision wanted.
//
// A profile meets the target when every term's predicted standard error is
// at most its target (studies/plan/design_precision.h); its shortfall is the
// largest ratio se_j / target_j (≤ 1: met), a nonlinear term with a target
// also counting se(ln θ_j) / kLogParameterSe (its parameter pinned down, or
// the prediction does not hold: studies/plan/design_precision.h).
//
// A recipe (studies/plan/profiles.h) has one length parameter: its range is
// scanned on a geometric grid from the shortest test to the longest, and the
// first grid step that meets the target is narrowed by bisection. A recipe
// that meets it nowhere within the longest test is reported as never (the
// precision is not monotone in length for every shape; the scan, not an
// assumption, finds the first length that works).
//
// The planned profile: legs alternating between the range's ends at the rate
// limit, 1 to kMostLegs of them, either end first, each with its own soak.
// For a shape u of the soaks (soak_i = s·u_i, a soak shorter than the
// minimum soak lengthened to it, u_i = 0 turning at once) the shortest scale
// s is found as for a recipe; the shape is improved by a pattern search
// (each soak doubled, halved or removed in turn, the best move kept, until
// none shortens the test); each family also tries turning at once at every
// end (all soaks 0). A candidate longer than the longest test allowed never
// meets the target. Every family runs on its own thread.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "studies/plan/design_precision.h"
#include "studies/plan/profiles.h"

namespace gyrotherm::studies::plan {

inline constexpr int kMostLegs = 6;

double shortfall(const Precision& p, const std::vector<double>& target);

struct Candidate {
  ChamberProfile profile;
  Precision precision;
  double shortfall = 0;
  bool fits = true;  // no longer than the longest test allowed
  bool met() const { return fits && shortfall <= 1.0; }
};

// A profile's prediction, judged against the target and the longest test.
Candidate candidate_of(const DesignEvaluator& evaluator, ChamberProfile profile, const std::vector<double>& target,
                       double longest_s);

struct SearchOutcome {
  bool met = false;
  Candidate best;  // the shortest that meets the target; else the one closest to it
  std::size_t evaluations = 0;
};

SearchOutcome shortest_recipe(const DesignEvaluator& evaluator, const Recipe& recipe,
                              const std::vector<double>& target);

// `progress(done, total)` after each family.
SearchOutcome shortest_plan(const DesignEvaluator& evaluator, const RigLimits& limits,
                            const std::vector<double>& target,
                            const std::function<void(int, int)>& progress = {});

}  // namespace gyrotherm::studies::plan
