#include "sim/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "sim/bias_model.h"
#include "sim/util/input_error.h"
#include "sim/noise.h"
#include "sim/util/random.h"

namespace gyrotherm::sim {
namespace {

using N = RigDynamics::Node;

// Largest |dT/dt| over the dynamic nodes, K/s.
double largest_rate(const RigDynamics& dynamics, double t, std::span<const double> y) {
  double worst = 0.0;
  for (double r : dynamics.observe(t, y).rates_k_per_s) worst = std::max(worst, std::abs(r));
  return worst;
}

}  // namespace

// The gyro's noise and the four temperature readings,, each from its own stream.
struct Simulator::NoiseSources {
  GyroNoise gyro;
  ReadingNoise chamber, case_, temp, temp2;
  std::vector<ReadingNoise> channels;  // the white noise of each channel
  void draw_ahead(std::size_t samples) {
    gyro.draw_ahead(samples);
    for (ReadingNoise* r : {&chamber, &case_, &temp, &temp2}) r->draw_ahead(samples);
  }
};

Simulator::NoiseSources Simulator::noise_sources() const {
  const SensorConfig& sensor = rig_.sensor;
  const std::uint64_t seed = scenario_.seed;
  NoiseSources sources{GyroNoise(gyro_.noise, 1.0 / scenario_.sample_rate_hz, seed),
                       ReadingNoise(sensor.noise_c, sensor.resolution_c, seed, streams::reading_base + 0),
                       ReadingNoise(sensor.noise_c, sensor.resolution_c, seed, streams::reading_base + 1),
                       ReadingNoise(sensor.noise_c, sensor.resolution_c, seed, streams::reading_base + 2),
                       ReadingNoise(sensor.noise_c, sensor.resolution_c, seed, streams::reading_base + 3),
                       {}};
  // A density in unit·√s scatters a sample at rate f by density·√f.
  for (std::size_t i = 0; i < gyro_.channels.size(); ++i)
    sources.channels.emplace_back(gyro_.channels[i].white_noise * std::sqrt(scenario_.sample_rate_hz), 0.0, seed,
                                  streams::channel_base + i);
  return sources;
}

std::size_t Simulator::sample_count() const {
  const double dt = 1.0 / scenario_.sample_rate_hz;
  const double total_s = Profile(scenario_.start_c, scenario_.segments).duration_s();
  return static_cast<std::size_t>(std::floor(total_s / dt + 1e-9)) + 1;  // as run_thermal
}

CvodeOptions SimulationOptions::default_solver_options() {
  CvodeOptions o;
  o.relative_tolerance = 1e-7;
  o.absolute_tolerance.assign(RigDynamics::kStateSize, 1e-6);  // K
  o.absolute_tolerance[RigDynamics::kIntegral] = 1e-3;           // W
  o.absolute_tolerance[RigDynamics::kHeaterEnergy] = 1.0;        // J
  o.absolute_tolerance[RigDynamics::kLossEnergy] = 1.0;          // J
  return o;
}

Simulator::Simulator(Scenario scenario, RigConfig rig, GyroConfig gyro, SimulationOptions options)
    : scenario_(std::move(scenario)),
      rig_(rig),
      gyro_(std::move(gyro)),
      options_(std::move(options)) {}

std::vector<double> Simulator::initial_state(const RigDynamics& dynamics) const {
  std::vector<double> y = dynamics.soaked_state(scenario_.start_c);
  if (scenario_.initial == InitialCondition::soaked) return y;

  // Steady: hold the start temperature with the gyro running until every node
  // has settled, checked once per simulated hour. With time constants up to a
  // few hours, |dT/dt| < 1e-12 K/s leaves less than ~1e-8 K to go.
  const Profile hold(scenario_.start_c, {Segment{SegmentKind::hold, scenario_.start_c, 0.0,
                                                 1e9, 0}});
  RigDynamics settling(rig_, hold, scenario_.room_c, scenario_.chamber);
  CvodeSolver solver(settling, 0.0, y, options_.solver);
  constexpr double kCheckS = 3600.0;
  constexpr double kLimitS = 1000.0 * 3600.0;
  for (double t_check = kCheckS; t_check <= kLimitS; t_check += kCheckS) {
    while (solver.time() < t_check) solver.step_towards(t_check);
    solver.state_at(t_check, y);
    if (largest_rate(settling, t_check, y) < 1e-12) {
      y[RigDynamics::kHeaterEnergy] = 0.0;
      y[RigDynamics::kLossEnergy] = 0.0;
      return y;
    }
  }
  throw InputError(scenario_.file.string() +
                   ": initial = \"steady\": the rig does not settle within 1000 h at start_c");
}

ThermalTrace Simulator::run_thermal(SolverStatistics* statistics, EnergyBalance* energy,
                                    SimulationObserver* observer) const {
  const Profile profile(scenario_.start_c, scenario_.segments);
  RigDynamics dynamics(rig_, profile, scenario_.room_c, scenario_.chamber);
  std::vector<double> y = initial_state(dynamics);
  const double stored_at_start = dynamics.stored_energy_j(y);

  const double dt = 1.0 / scenario_.sample_rate_hz;
  const double total_s = profile.duration_s();
  const auto samples = static_cast<std::size_t>(std::floor(total_s / dt + 1e-9)) + 1;

  ThermalTrace trace;
  trace.time_s.reserve(samples);
  for (auto& column : trace.node_c) column.reserve(samples);
  trace.anode_rate_c_per_s.reserve(samples);
  trace.setpoint_c.reserve(samples);
  trace.heater_w.reserve(samples);

  auto record = [&](double t, std::span<const double> state) {
    const RigDynamics::Sample o = dynamics.sample(t, state);
    trace.time_s.push_back(t);
    for (std::size_t i = 0; i < RigDynamics::node_count; ++i) trace.node_c[i].push_back(state[i]);
    trace.anode_rate_c_per_s.push_back(o.anode_rate_k_per_s);
    trace.setpoint_c.push_back(o.setpoint_c);
    trace.heater_w.push_back(o.heater_w);
  };

  CvodeSolver solver(dynamics, 0.0, y, options_.solver);
  CvodeSolver::StepPolynomial step;
  record(0.0, y);
  std::size_t k = 1;
  const std::size_t segments = profile.segments().size();
  for (std::size_t s = 0; s < segments; ++s) {
    const double breakpoint = profile.segment_end_s(s);
    if (breakpoint <= solver.time()) continue;  // a segment of zero length
    while (solver.time() < breakpoint) {
      const double t = solver.step_towards(breakpoint);
      if (k < samples && static_cast<double>(k) * dt <= t) solver.step_polynomial(step);
      for (; k < samples && static_cast<double>(k) * dt <= t; ++k) {
        const double tk = static_cast<double>(k) * dt;
        // The nodes and the controller's integral: all a sample records.
        const std::span<double> needed = std::span<double>(y).first(RigDynamics::kIntegral + 1);
        step.evaluate(tk, needed);
        record(tk, y);
      }
    }
    if (observer != nullptr) observer->on_progress(breakpoint, total_s);
    if (s + 1 < segments) {
      // The right-hand side is discontinuous here (a ramp ends, the chamber
      // switches off): restart so the BDF history never spans the break.
      solver.state_at(breakpoint, y);
      solver.restart(breakpoint, y);
    }
  }
  solver.state_at(solver.time(), y);
  if (statistics != nullptr) *statistics = solver.statistics();
  if (energy != nullptr) {
    energy->stored_change_j = dynamics.stored_energy_j(y) - stored_at_start;
    energy->heater_j = y[RigDynamics::kHeaterEnergy];
    energy->lost_j = y[RigDynamics::kLossEnergy];
    energy->self_heating_j = dynamics.self_heating_w() * solver.time();
  }
  return trace;
}

SimulationResult Simulator::run(SimulationObserver* observer) const {
  SolverStatistics solver;
  EnergyBalance energy;
  NoiseSources noise = noise_sources();
  ThermalTrace trace;
  {
    std::jthread drawer([&] { noise.draw_ahead(std::min(sample_count(), kDrawAheadSamples)); });
    trace = run_thermal(&solver, &energy, observer);
  }  // joined here, or on the way out of an error
  SimulationResult result = record(std::move(trace), noise, true);
  result.solver = solver;
  result.energy = energy;
  return result;
}

SimulationResult Simulator::record(ThermalTrace trace) const {
  NoiseSources noise = noise_sources();
  return record(std::move(trace), noise, false);
}

SimulationResult Simulator::record(ThermalTrace trace, NoiseSources& sources, bool parallel) const {
  SimulationResult result;
  result.seed = scenario_.seed;
  result.truth = std::move(trace);
  const ThermalTrace& tr = result.truth;
  const std::size_t n = tr.time_s.size();
  const double dt = 1.0 / scenario_.sample_rate_hz;
  GyroNoise& noise = sources.gyro;
  ReadingNoise& read_chamber = sources.chamber;
  ReadingNoise& read_case = sources.case_;
  ReadingNoise& read_temp = sources.temp;
  ReadingNoise& read_temp2 = sources.temp2;

  for (auto* column : {&result.time_s, &result.chamber_c, &result.case_c, &result.temp_c,
                       &result.temp2_c, &result.gyro_dph})
    column->reserve(n);

  // 2. The true state the effects read: the anode side's temperature, its
  // exact dT/dt, d²T/dt² by central differences (one-sided at the ends), the
  // far side; switched on at the start of a soaked record.
  effects::EffectSeries state;
  state.time_s = tr.time_s;
  state.temp_c = tr.node_c[N::anode];
  state.temp2_c = tr.node_c[N::far];
  state.rate_c_per_s = tr.anode_rate_c_per_s;
  state.switch_on_s = scenario_.initial == InitialCondition::soaked
                          ? 0.0
                          : -std::numeric_limits<double>::infinity();
  const std::vector<double>& rate = tr.anode_rate_c_per_s;
  state.accel_c_per_s2.assign(n, 0.0);
  for (std::size_t k = 0; n > 1 && k < n; ++k) {
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = k + 1 == n ? k : k + 1;
    state.accel_c_per_s2[k] = (rate[hi] - rate[lo]) / (static_cast<double>(hi - lo) * dt);
  }

  // 3. The true bias, then the pulse-counted output and the readings.
  //    The readings depend on nothing the gyro's column does: with `parallel`
  //    they are made on a second thread (each column from its own stream, so
  //    the values are the same).
  auto readings = [&] {
    for (std::size_t k = 0; k < n; ++k) {
      result.chamber_c.push_back(read_chamber.read(tr.node_c[N::chamber][k]));
      result.case_c.push_back(read_case.read(tr.node_c[N::case_][k]));
      result.temp_c.push_back(read_temp.read(tr.node_c[N::sensor][k]));
      result.temp2_c.push_back(read_temp2.read(tr.node_c[N::sensor2][k]));
    }
  };
  std::jthread reader;  // joined on the way out, errors included
  if (parallel) reader = std::jthread(readings);
  result.time_s = tr.time_s;
  result.bias_true_dph = BiasModel(gyro_).bias_dph(state);
  for (std::size_t k = 0; k < n; ++k)
    result.gyro_dph.push_back(noise.sample(result.bias_true_dph[k], state.temp_c[k]));
  for (std::size_t i = 0; i < gyro_.channels.size(); ++i) {
    SimulationResult::Channel channel;
    channel.truth = BiasModel(gyro_.channels[i], gyro_).bias_dph(state);
    channel.value.reserve(n);
    for (const double v : channel.truth) channel.value.push_back(sources.channels[i].read(v));
    result.channels.push_back(std::move(channel));
  }
  if (parallel)
    reader.join();
  else
    readings();
  return result;
}

double soak_control_error_c(const Scenario& sc, const ThermalTrace& tr) {
  if (!sc.chamber) return 0.0;
  const Profile profile(sc.start_c, sc.segments);
  double worst = 0.0;
  for (std::size_t k = 0; k < tr.time_s.size(); ++k) {
    const std::size_t s = profile.segment_at(tr.time_s[k]);
    if (profile.segments()[s].kind != SegmentKind::hold) continue;
    if (tr.time_s[k] < profile.segment_start_s(s) + 600.0) continue;
    worst = std::max(worst, std::abs(tr.node(RigDynamics::chamber)[k] - tr.setpoint_c[k]));
  }
  return worst;
}

}  // namespace gyrotherm::sim
