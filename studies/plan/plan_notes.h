#pragma once
// What a plan states beside its profile, as data: the thermal path it
// integrated, and what it assumed or changed that the options did not ask
// for (a start clamped into --range, noise bounds it used at their
// estimate, a Gauss–Markov process merged into the flicker bank, a
// parameter taken as known, a recipe that beat the searched family).
// thermal_path_text and note_text word them for the text report, the JSON
// and the files' headers.

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace gyrotherm::studies::plan {

// The first-order lag of --tau, or the rig file's thermal network.
struct ThermalPath {
  std::optional<double> tau_s;
  std::string rig_file, scenario_file;  // file names (without --tau)
};
std::string thermal_path_text(const ThermalPath& path);

// The scenario starts outside --range: the tests start soaked at its nearer end.
struct StartClamped {
  double scenario_c = 0, start_c = 0;
};
// --noise FILE's components the record did not pin down, used at their estimate.
struct LooseNoise {
  struct Component {
    std::string name, unit;
    double bound = 0;  // the upper end of its 95 % interval
  };
  std::string file;  // its name
  std::vector<Component> components;
};
// A Gauss–Markov process beside a flicker bank, merged into it by its
// variance (a gyro file has one bank).
struct GaussMarkovMerged {
  double sigma_dph = 0, tau_s = 0;
  double bank_b_dph = 0, merged_b_dph = 0;  // the bank's bias instability before and after
  int processes = 0;
  double tau_min_s = 0, tau_max_s = 0;
};
// A nonlinear term without a prior coefficient: its parameter is taken as known.
struct ParameterAssumed {
  std::string term, parameter;
  double value = 0;
};
// A standard recipe was shorter than every profile of the searched family.
struct RecipeIsPlan {
  std::string recipe;
};
// The warm-up from cold meets the precision sooner than the plan, but its
// cold soak (unpowered, at the range's low end) is not counted: it is never the plan.
struct WarmupNotCounted {
  double duration_s = 0, low_c = 0, start_c = 0;
};
using PlanNote =
    std::variant<StartClamped, LooseNoise, GaussMarkovMerged, ParameterAssumed, RecipeIsPlan, WarmupNotCounted>;
std::string note_text(const PlanNote& note);

}  // namespace gyrotherm::studies::plan
