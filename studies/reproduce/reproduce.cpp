#include "studies/reproduce/reproduce.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "studies/simulated.h"
#include "fit/model/formula.h"
#include "sim/config_loader.h"
#include "sim/util/format.h"

namespace gyrotherm::studies {
namespace {

ScenarioFacts facts_of(const sim::Scenario& sc, const sim::SimulationResult& run) {
  ScenarioFacts f;
  f.duration_h = sim::Profile(sc.start_c, sc.segments).duration_s() / 3600.0;
  f.room_c = sc.room_c;
  f.chamber = sc.chamber;
  f.set_min_c = f.set_max_c = sc.start_c;
  for (const sim::Segment& s : sc.segments) {
    if (s.kind == sim::SegmentKind::free) continue;
    f.set_min_c = std::min(f.set_min_c, s.temp_c);
    f.set_max_c = std::max(f.set_max_c, s.temp_c);
  }
  if (run.rows() > 0) {
    const auto [lo, hi] = std::minmax_element(run.temp_c.begin(), run.temp_c.end());
    f.gyro_min_c = *lo;
    f.gyro_max_c = *hi;
  }
  return f;
}

sim::SimulationResult simulate(const std::filesystem::path& file, std::uint64_t* seed, ScenarioFacts* facts) {
  const sim::Scenario sc = sim::load_scenario(file);
  const sim::RigConfig rig = sim::load_rig(sc.rig_file);
  const sim::GyroConfig gyro = sim::load_gyro(sc.gyro_file);
  sim::check_scenario_against_rig(sc, rig, sc.rig_file);
  *seed = sc.seed;
  sim::SimulationResult run = sim::Simulator(sc, rig, gyro).run();
  *facts = facts_of(sc, run);
  return run;
}

Truth truth_of(const std::filesystem::path& cycle) {
  const sim::Scenario sc = sim::load_scenario(cycle);
  const sim::GyroConfig g = sim::load_gyro(sc.gyro_file);
  Truth t;
  t.coefficients = sim::true_coefficients(g);
  return t;
}

}  // namespace

std::string ScenarioFacts::text() const {
  const std::string where = chamber ? fmt::format("in the chamber, set points {} °C", range_text(set_min_c, set_max_c, 0))
                                    : fmt::format("in a {:g} °C room", room_c);
  return fmt::format("{}, {:g} h", where, std::round(duration_h * 10.0) / 10.0);
}

ReproduceResult reproduce(const ReproduceOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  auto progress = [&](const std::string& step, double f) {
    if (o.progress) o.progress(step, f);
  };
  ReproduceResult r;
  std::vector<std::string> engines = o.engines;
  if (engines.empty())
    for (const fit::EngineInfo& e : fit::engine_registry())
      if (e.minimises_sigma) engines.push_back(e.name);
  for (const std::string& e : engines) fit::find_engine(e);  // fail early on a bad name

  progress("simulating the cycle", 0.0);
  r.cycle_run = simulate(o.cycle, &r.cycle_seed, &r.cycle_facts);
  progress("simulating Test 1 (random profile)", 0.05);
  r.test1_run = simulate(o.test1, &r.test1.seed, &r.test1.facts);
  progress("simulating Test 2 (natural warm-up)", 0.2);
  r.test2_run = simulate(o.test2, &r.test2.seed, &r.test2.facts);
  r.truth = truth_of(o.cycle);

  const fit::PipelineOptions pipeline;  // the paper's: glitches removed, 100 s, central differences
  r.cycle_data = fit::prepare_data(measurement_of(r.cycle_run, "cycle"), pipeline);
  const std::vector<const fit::Term*> terms = fit::parse_formula(fit::kDefaultModel);
  const fit::Measurement test1 = measurement_of(r.test1_run, "test1");
  const fit::Measurement test2 = measurement_of(r.test2_run, "test2");
  fit::PipelineOptions causal = pipeline;
  causal.derivative = fit::DerivativeMode::causal;
  r.test1.name = "test1";
  r.test2.name = "test2";

  for (std::size_t i = 0; i < engines.size(); ++i) {
    progress(fmt::format("fitting the cycle with {}", engines[i]),
             0.25 + (kReproduceComputedShare - 0.25) * static_cast<double>(i) / static_cast<double>(engines.size()));
    fit::EngineSettings settings;
    settings.seed = o.engine_seed;
    EngineOnCycle e;
    e.engine = engines[i];
    e.fit = fit::fit_model(r.cycle_data, terms, fit::find_engine(engines[i]), settings);
    e.coefficient_error = coefficient_errors(e.fit, r.truth);
    r.cycle_raw_dph = e.fit.instability_before_dph;

    fit::SavedFit saved;
    saved.engine = e.engine;
    saved.terms = terms;
    saved.parameters = e.fit.parameters;
    saved.coefficients = e.fit.coefficients;
    saved.pipeline = causal;
    r.test1.by_engine[e.engine] = fit::compensate(test1, saved, causal);
    r.test2.by_engine[e.engine] = fit::compensate(test2, saved, causal);
    r.test1.before_dph = r.test1.by_engine[e.engine].before_dph;
    r.test2.before_dph = r.test2.by_engine[e.engine].before_dph;
    r.engines.push_back(std::move(e));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace gyrotherm::studies
