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
  std::string target_from; // "--se", "--rel-se 0.3", "--separate", "detect"
  double predicted_se = 0;
  double parameter = 0;         // a nonlinear term's θ (NaN without one)
  double parameter_log_se = 0;  // its predicted se of ln θ (NaN: none predicted)
};

struct Baseline {
  std::string recipe, about;
  bool met = false;
  double duration_s = 0;   // the shortest that meets the target (when met)
  double shortfall = 0;    // else: the closest's largest se / target
  double closest_s = 0;    // and its length
  std::string why;         // what holds it back when not met
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
  std::string thermal_path;  // "rig_shield.toml (scenario cycle.toml)" / "first-order lag, τ = 1800 s"
  std::string noise;         // the noise's description and source
  ChamberProfile profile;
  double duration_s = 0;
  double sensor_min_c = 0, sensor_max_c = 0;
  std::size_t windows = 0;
  std::vector<Baseline> baselines;
  std::optional<Verification> verification;
  std::string scenario_file, setpoint_file, rig_file, gyro_file, figure_file;
  std::vector<std::string> notes;
  std::size_t evaluations = 0;
  double seconds = 0;
};

struct PlanProgress {
  std::function<void(const std::string& stage, int done, int total)> report;
};

// Throws InputError (exit 2, nothing written) for bad options, and when no
// profile within the limits meets the target (saying what limits it).
PlanResult run_plan(const PlanRequest& request, const PlanProgress& progress = {});

nlohmann::ordered_json plan_json(const PlanResult& result);
std::string plan_text(const PlanResult& result);

}  // namespace gyrotherm::studies::plan
