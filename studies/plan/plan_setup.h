#pragma once
// From `gyrotherm plan`'s options to what the search needs: the base
// scenario, the thermal path, the gyro and its noise, the model with its
// priors and targets, and the rig's limits (studies/plan/plan.h says what
// each option means). Every option is checked here: InputError names it.

#include <filesystem>
#include <string>
#include <vector>

#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"
#include "studies/plan/design_precision.h"
#include "studies/plan/plan.h"

namespace gyrotherm::studies::plan {

struct PlanSetup {
  sim::Scenario base;  // room, start, initial condition, chamber, seed (the prediction samples at kPredictionRateHz)
  sim::RigConfig rig;
  sim::GyroConfig gyro;  // the truth --verify simulates (priors as coefficients where it had none)
  PlanNoise noise;
  bool noise_from_gyro_file = true;
  std::string model_text;  // the model as given (--model, a diagnosis's, or the default)
  PlanModel model;
  std::vector<TermPlan> terms;
  RigLimits limits;
  ThermalPath thermal_path;
  std::vector<PlanNote> notes;
};

PlanSetup plan_setup(const PlanRequest& request);

// A rig whose sensor follows the chamber air as a first-order lag of tau_s
// (the case is the one slow node, the block and sensor follow it within a
// second, no self-heating); the chamber is `chamber_of`'s.
sim::RigConfig first_order_rig(double tau_s, const sim::RigConfig& chamber_of);

// The sample rate of the prediction's thermal trace: the temperatures are
// smooth over seconds, and 10 s samples give the 100 s window means and the
// standard errors to three or four digits (against 1 Hz on the cycle, for
// T + T^2 + T^3 + dT + T*dT + d2T) at a tenth of the cost.
inline constexpr double kPredictionRateHz = 0.1;

}  // namespace gyrotherm::studies::plan
