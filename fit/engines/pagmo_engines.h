#pragma once
// pagmo2 engines: four population-based optimisers of ESA's pagmo2 library
// run through one adapter, registered as
//
//   pso    particle swarm, pagmo::pso (Clerc's constriction variant by default;
//          Poli, Kennedy & Blackwell, Swarm Intelligence 1, 33–57, 2007)
//   de     differential evolution, pagmo::de (DE/rand/1/exp by default;
//          Storn & Price, J. Global Optim. 11, 341–359, 1997)
//   cmaes  covariance matrix adaptation, pagmo::cmaes (Hansen, "The CMA
//          Evolution Strategy: A Tutorial", arXiv:1604.00772)
//   abc    artificial bee colony, pagmo::bee_colony (Karaboga & Basturk,
//          J. Global Optim. 39, 459–471, 2007)
//
// Each minimises σ(z) = LinearProblem::objective(z) over the unit box
// z ∈ [−1, 1]^m. The adapter is a pagmo user-defined problem whose fitness is
// the engine's Evaluator, so every evaluation — the initial population too —
// is counted, and the best point and history are kept, exactly as for the
// hand-written engines. One generic engine class is parameterised by a recipe:
// the population size, the evaluations one generation costs, and a function
// that builds the pagmo algorithm for a number of generations and a seed.
//
// Exact stopping. pagmo algorithms run whole generations and know nothing of
// a budget or a target, so the problem's fitness throws a private exception
// once the Evaluator is done (budget spent, or σ ≤ target): the evaluation
// that spends the budget or reaches the target is the last one. The adapter
// catches it around the population's construction and evolve(). pagmo lets it
// through: problem::fitness and algorithm::evolve document "throws any
// exception thrown by the UDP/UDA", the four algorithms evaluate serially in
// the calling thread (no batch evaluator is used), and the problem declares
// thread_safety::none so pagmo never evaluates it from another thread.
// The algorithm is evolved once, for as many generations as the budget can
// pay for, rather than one generation per call: bee_colony keeps its
// abandonment counters (`limit`) in local variables of evolve(), so it only
// abandons food sources within one multi-generation call; one mechanism then
// serves all four, and none needs a memory flag. Generations are counted from
// evaluations — pso, de and cmaes spend exactly one evaluation per individual
// per generation, bee_colony exactly two (employed + onlooker phases; a scout
// replaces one employed evaluation) — which drives FitObserver::on_iteration
// once per generation (returning false stops the run, Termination::stopped)
// and FitResult::iterations (completed generations; a generation cut short by
// the budget or the target is not counted). de and cmaes may also end by
// themselves when their population collapses (xtol/ftol): Termination::converged.
// A non-finite candidate (which σ's Gram form would score 0) also ends the run
// as converged instead of being evaluated.
//
// Seeds. EngineSettings::seed (64-bit) is mixed by SplitMix64 into two 32-bit
// seeds, one for the population's random start and one for the algorithm;
// the same seed gives a bit-identical FitResult (apart from seconds).
//
// Defaults are pagmo's own, except where the problem needs otherwise:
//   population  pagmo leaves it to the caller. pso: 0 = 10 + ⌊2√m⌋ (Clerc's
//               SPSO 2007 swarm); cmaes: 0 = 4 + ⌊3 ln m⌋ (Hansen's λ);
//               de and abc: 20.
//   abc limit   0 = population·m (Karaboga & Basturk's SN·D; pagmo: 20). With
//               20 the colony abandons sources near the optimum before they
//               converge: on the 3-term test 3 of 20 seeds stalled 2e-5 above
//               the optimal σ for 200 000 evaluations.
//   de, cmaes   ftol = 0 (pagmo: 1e-6) — an absolute tolerance in σ's units,
//               which would stop a fit whose σ is ~1e-2 °/h long before it is
//               accurate; xtol = 1e-12 (pagmo: 1e-6) — in the unit box 1e-6
//               can still be far from the optimum when the terms are
//               correlated; 1e-12 stops only a collapsed population (and keeps
//               CMA-ES's step size from underflowing to NaN).
//   cmaes       force_bounds is always on: the Evaluator clamps into the box,
//               so CMA-ES must not learn from points it did not evaluate.
// An option's rule is checked when the engine is made; a bad one throws
// InputError naming the engine, the option, its value and the rule.

#include <vector>

#include "fit/engines/engine.h"

namespace gyrotherm::fit {

// Evaluations when EngineSettings::max_evaluations is 0.
inline constexpr long kPagmoDefaultEvaluations = 20000;

// Registry entries for pso, de, cmaes and abc (in that order).
std::vector<EngineInfo> pagmo_engine_infos();

}  // namespace gyrotherm::fit
