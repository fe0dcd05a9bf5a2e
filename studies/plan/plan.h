#pragma once
// `gyrotherm plan`: the shortest chamber test that identifies a bias model to
// the precision wanted, under the gyro's own noise, at the rig's limits —
// and the standard recipes' durations for the same precision.
//
//   the model      --model; --separate adds a group of terms that must be
//                  told apart (each fitted with the others and the model);
//   the precision  --se TERM=VALUE (the coefficient's unit), --rel-se
//                  [TERM=]FRACTION (of a prior value); a --separate member:
//                  found at p < 0.01 with 90 % power at its prior size,
//                  se ≤ |prior| / (z_0.995 + z_0.90) = |prior| / 3.86; with
//                  none of these, every model term with a prior the same
//                  (detected at p < 0.01 with 90 % power);
//   the priors     the gyro file's [truth] and [hidden] values, replaced by
//                  a fit JSON's coefficients (--noise FIT.json), by the
//                  sizes given in --separate NAME=SIZE and by --prior
//                  TERM=VALUE; --verify simulates a gyro with these values;
//   the noise      the gyro file's [noise] (default: the scenario's gyro),
//                  or --noise FILE.json (studies/plan/plan_noise.h);
//   the rig        the scenario's (default scenarios/cycle.toml: room,
//                  start temperature, rig and gyro), --rig, or --tau S: a
//                  first-order thermal path of S seconds from chamber to
//                  sensor; the limits --range, --max-rate, --min-soak,
//                  --longest (studies/plan/profiles.h).
//
// The search is studies/plan/search.h, the prediction
// studies/plan/design_precision.h; --verify N simulates the planned test N
// times and fits each (studies/plan/verify.h).
//
// Files in --out DIR (written only once everything is computed; each
// atomically): plan.toml (a scenario `gyrotherm simulate` runs as is), the
// rig and gyro files it names (rig.toml, gyro.toml), plan_setpoint.csv
// (time_s, setpoint_c: the chamber programme at 10 s), plan.png (the
// profile, the sensor's temperature and where each coefficient's
// information comes from).

#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "studies/plan/plan_noise.h"
#include "studies/plan/plan_notes.h"
#include "studies/plan/precision.h"
#include "studies/plan/profiles.h"

namespace gyrotherm::studies::plan {

// z_0.995 + z_0.90: a coefficient of this many standard errors is found at
// p < 0.01 (two-sided) in 90 % of tests.
inline constexpr double kDetectableInSe = 2.5758293035489 + 1.2815515655446;

struct PlanRequest {
  std::string model;                  // "": a --separate diagnosis's model, else fit::kDefaultModel
  std::vector<std::string> se;        // TERM=VALUE
  std::vector<std::string> rel_se;    // FRACTION or TERM=FRACTION
  std::vector<std::string> separate;  // NAME[=SIZE], or one diagnose JSON
  std::vector<std::string> param;     // NAME=VALUE: a nonlinear term's parameter
  std::vector<std::string> prior;     // TERM=VALUE: a coefficient's prior value
  std::string scenario;               // "": the built-in default (scenarios/cycle.toml)
  std::string rig, gyro, noise;       // override the scenario's / the gyro's noise
  std::optional<double> tau_s;        // a first-order thermal path instead of a rig
  std::optional<std::pair<double, double>> range_c;  // default: the scenario's set points
  std::optional<double> max_rate_c_per_min;           // default: the scenario's fastest ramp
  double min_soak_s = 0.0;
  double longest_h = 72.0;
  std::string out = "plan";
  int verify = 0;
  std::optional<std::uint64_t> seed;  // the first of --verify's seeds (default: the scenario's)
};

struct TermPlan {
  std::string term;
  std::string unit;        // of the coefficient
  double prior = 0;        // 0: none
  double target_se = 0;    // +∞: no target (reported only)
  // Where the target came from (target_from_text words it): --se, --rel-se
  // (rel_se_given: the option's value as given), --separate, or a prior to
  // detect; none: no target.
  enum class TargetFrom { none, se, rel_se, separate, detect } target_from = TargetFrom::none;
  std::string rel_se_given;
  double predicted_se = 0;
  double parameter = 0;         // a nonlinear term's θ (NaN without one)
  double parameter_log_se = 0;  // its predicted se of ln θ (NaN: none predicted)
};

struct Baseline {
  std::string recipe, about;  // the recipe's name and its registry description
  bool met = false;
  double duration_s = 0;   // the shortest that meets the target (when met)
  double shortfall = 0;    // else: the closest's largest se / target
  // Else the closest, and what holds it back (baseline_why words it): its
  // precision (its length; a refusal, or the terms short of their targets),
  // or a test longer than --longest.
  Precision closest;
  bool too_long = false;
};

struct Verification {
  int seeds = 0;
  std::uint64_t first_seed = 0;
  std::vector<double> achieved_se, mean_reported_se, coverage_95, truth;  // per term
  double seconds = 0;
};

struct PlanResult {
  PlanRequest request;
  std::string model;  // the model fitted: the one asked for and the group to separate
  std::vector<TermPlan> terms;
  RigLimits limits;
  ThermalPath thermal_path;
  PlanNoise noise;           // the noise predicted under (noise_text words it and its source)
  ChamberProfile profile;
  double duration_s = 0;
  double sensor_min_c = 0, sensor_max_c = 0;
  std::size_t windows = 0;
  std::vector<Baseline> baselines;
  std::optional<Verification> verification;
  std::string scenario_file, setpoint_file, rig_file, gyro_file, figure_file;
  std::vector<PlanNote> notes;
  std::size_t evaluations = 0;
  double seconds = 0;
};

struct PlanProgress {
  std::function<void(const std::string& stage, int done, int total)> report;
};

// Throws InputError (exit 2, nothing written) for bad options, and when no
// profile within the limits meets the target (saying what limits it).
PlanResult run_plan(const PlanRequest& request, const PlanProgress& progress = {});

// What holds a baseline back (empty when it is met): a refusal, a test
// longer than --longest, or each term short of its target.
std::string baseline_why(const Baseline& baseline, const PlanResult& result);
// "--se", "--rel-se 0.3", "--separate (p < 0.01, 90 % power)", "detect (…)"; "" without a target.
std::string target_from_text(const TermPlan& term);
// The noise's description and, in parentheses, its source.
std::string noise_text(const PlanNoise& noise);

nlohmann::ordered_json plan_json(const PlanResult& result);
std::string plan_text(const PlanResult& result);

}  // namespace gyrotherm::studies::plan
