#pragma once
// The thermal-test simulator: a scenario (profile), a rig (thermal network and
// chamber) and a gyro (true bias model and noise) in; a sampled record out.
//
// 1. Integrate the rig's ODE (sim/rig_dynamics.h) with CVODE, stopping and
//    restarting at every profile breakpoint, and sample the true temperatures
//    and dT/dt of the anode side at the scenario's sample rate (dense output).
// 2. d²T/dt² by central differences of the exact dT/dt samples.
// 3. True bias B(t) from sim/bias_model.h, then the pulse-counted output with
//    noise (sim/noise.h); temperature readings with sensor noise and resolution.
//
// Every random draw comes from the scenario's seed; the same inputs give
// bit-identical results. The simulator never prints: progress goes to an
// observer.

#include <array>
#include <cstdint>
#include <vector>

#include "sim/cvode_solver.h"
#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/rig_dynamics.h"
#include "sim/scenario.h"

namespace gyrotherm::sim {

// The true physical temperatures at the sample times.
struct ThermalTrace {
  std::vector<double> time_s;
  std::array<std::vector<double>, RigDynamics::node_count> node_c;  // by RigDynamics::Node
  std::vector<double> anode_rate_c_per_s;  // exact dT/dt from the right-hand side
  std::vector<double> setpoint_c;
  std::vector<double> heater_w;            // controller output (+ heating, − cooling)
  const std::vector<double>& node(RigDynamics::Node n) const { return node_c[n]; }
};

// Σ C_i ΔT_i = heater + self-heating − lost; the residual measures the integration error.
struct EnergyBalance {
  double stored_change_j = 0.0;
  double heater_j = 0.0;
  double self_heating_j = 0.0;
  double lost_j = 0.0;
  double residual_j() const { return stored_change_j - (heater_j + self_heating_j - lost_j); }
};

struct SimulationOptions {
  CvodeOptions solver = default_solver_options();
  static CvodeOptions default_solver_options();
};

struct SimulationResult {
  ThermalTrace truth;
  // The record, as the CSV has it.
  std::vector<double> time_s, chamber_c, case_c, temp_c, temp2_c, gyro_dph, bias_true_dph;
  // The gyro file's channels (sim/channel.h), in its order: the reading and
  // the noise-free value, in the channel's unit.
  struct Channel {
    std::vector<double> value, truth;
  };
  std::vector<Channel> channels;
  SolverStatistics solver;
  EnergyBalance energy;
  std::uint64_t seed = 0;
  std::size_t rows() const { return time_s.size(); }
};

class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  virtual void on_progress(double simulated_s, double total_s) = 0;
};

class Simulator {
 public:
  Simulator(Scenario scenario, RigConfig rig, GyroConfig gyro, SimulationOptions options = {});

  // Step 1 alone: the true temperatures.
  ThermalTrace run_thermal(SolverStatistics* statistics = nullptr,
                           EnergyBalance* energy = nullptr,
                           SimulationObserver* observer = nullptr) const;
  // Steps 1–3. The noise's Gaussian variates (which depend on nothing but the
  // seed) are drawn on a second thread while CVODE integrates, for up to
  // kDrawAheadSamples samples (the rest as they are needed), and the
  // temperature readings are made there while the gyro's column is; the
  // result is bit-identical to drawing and reading sample by sample.
  SimulationResult run(SimulationObserver* observer = nullptr) const;
  static constexpr std::size_t kDrawAheadSamples = std::size_t{1} << 19;  // 146 h at 1 Hz, 50 MB
  // Steps 2–3 on a trace that run_thermal() gave for this scenario's profile
  // and rig: the trace depends on neither the seed nor the gyro's [truth] and
  // [noise], so a campaign over seeds (studies/score/campaign.h) integrates it once. The
  // result is bit-identical to run()'s; its solver and energy fields are empty.
  SimulationResult record(ThermalTrace trace) const;

  const Scenario& scenario() const { return scenario_; }
  const RigConfig& rig() const { return rig_; }
  const GyroConfig& gyro() const { return gyro_; }

 private:
  std::vector<double> initial_state(const RigDynamics& dynamics) const;
  struct NoiseSources;
  NoiseSources noise_sources() const;
  // With `parallel`, the temperature readings on a second thread.
  SimulationResult record(ThermalTrace trace, NoiseSources& noise, bool parallel) const;
  std::size_t sample_count() const;

  Scenario scenario_;
  RigConfig rig_;
  GyroConfig gyro_;
  SimulationOptions options_;
};

// Worst |chamber − set point| over the soaks, skipping the first 10 min after
// each step (what a chamber's data sheet calls its control accuracy); 0
// without a chamber.
double soak_control_error_c(const Scenario& scenario, const ThermalTrace& trace);

}  // namespace gyrotherm::sim
