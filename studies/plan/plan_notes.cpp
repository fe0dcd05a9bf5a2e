#include "studies/plan/plan_notes.h"

#include <fmt/format.h>

#include "sim/util/format.h"

namespace gyrotherm::studies::plan {

std::string thermal_path_text(const ThermalPath& path) {
  if (path.tau_s) return fmt::format("first-order lag from the chamber air to the sensor, τ = {:g} s", *path.tau_s);
  return fmt::format("{} (the thermal network of {})", path.rig_file, path.scenario_file);
}

namespace {

struct NoteWords {
  std::string operator()(const StartClamped& n) const {
    return fmt::format("the scenario starts at {} °C, outside --range: the tests start soaked at {} °C",
                       n.scenario_c, n.start_c);
  }
  std::string operator()(const LooseNoise& n) const {
    std::string loose;
    for (const LooseNoise::Component& c : n.components)
      loose += fmt::format("{}{} (≤ {:.3g} {})", loose.empty() ? "" : ", ", c.name, c.bound, c.unit);
    return fmt::format("{}'s record did not pin down {}: each is used at its estimate, so the predicted errors are "
                       "optimistic where the noise is nearer its bound",
                       n.file, loose);
  }
  std::string operator()(const GaussMarkovMerged& n) const {
    return fmt::format(
        "the Gauss–Markov process (σ = {:.3g} °/h, τ = {} s) is merged into the flicker bank by its variance "
        "(a gyro file has one bank): bias_instability_dph {:.3g} → {:.3g} °/h over {} processes {:g}..{:g} s",
        n.sigma_dph, human(n.tau_s), n.bank_b_dph, n.merged_b_dph, n.processes, n.tau_min_s, n.tau_max_s);
  }
  std::string operator()(const ParameterAssumed& n) const {
    return fmt::format("{}'s {} is taken as known ({:g}): without a prior coefficient its uncertainty cannot be "
                       "predicted",
                       n.term, n.parameter, n.value);
  }
  std::string operator()(const WarmupNotCounted& n) const {
    return fmt::format("the warm-up from cold meets the precision in {:.2f} h, sooner than this plan, but only after "
                       "a cold soak at {} °C unpowered that it does not count (hours for the unit to get there); the "
                       "plan starts soaked at {} °C and counts all its time: take the warm-up where the unit can be "
                       "cold-soaked beforehand",
                       n.duration_s / 3600.0, n.low_c, n.start_c);
  }
  std::string operator()(const RecipeIsPlan& n) const {
    return fmt::format("the planned test is the recipe '{}': no profile of the searched family (full-range legs at "
                       "the rate limit) was shorter",
                       n.recipe);
  }
};

}  // namespace

std::string note_text(const PlanNote& note) { return std::visit(NoteWords{}, note); }

}  // namespace gyrotherm::studies::plan
