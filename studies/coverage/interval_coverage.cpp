#include "studies/coverage/interval_coverage.h"

#include <cmath>
#include <map>
#include <stdexcept>

#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/simulator.h"
#include "studies/simulated.h"

namespace gyrotherm::studies {

const std::vector<std::string>& noise_variant_names() {
  static const std::vector<std::string> names = {"white",        "white+flicker", "flicker",
                                                 "white+gm1000", "white+gm3600",  "white+rrw"};
  return names;
}

sim::NoiseConfig noise_variant(const std::string& name, sim::NoiseConfig n) {
  // A single Gauss–Markov process is the flicker bank with one member; its
  // Allan peak 4e-4 °/h is a process of σ ≈ 6.4e-4 °/h.
  auto gauss_markov = [&](double tau_s) {
    n.flicker_processes = 1;
    n.flicker_tau_min_s = n.flicker_tau_max_s = tau_s;
    n.bias_instability_dph = 4e-4;
  };
  if (name == "white") {
    n.bias_instability_dph = 0.0;
  } else if (name == "white+flicker") {
  } else if (name == "flicker") {
    n.arw_deg_per_sqrt_h = 0.0;
    n.quantization_arcsec = 0.0;
  } else if (name == "white+gm1000") {
    gauss_markov(1000.0);
  } else if (name == "white+gm3600") {
    gauss_markov(3600.0);
  } else if (name == "white+rrw") {
    n.bias_instability_dph = 0.0;
    n.rrw_dph_per_sqrt_h = 5e-4;
  } else {
    throw std::invalid_argument("unknown noise variant '" + name + "'");
  }
  return n;
}

Coverage interval_coverage(const sim::Scenario& scenario, const sim::RigConfig& rig,
                           const sim::GyroConfig& gyro, const CoverageOptions& options) {
  return interval_coverage(scenario, rig, gyro, options, {CoverageMethod{"ols", options.intervals, 0.0}}).front();
}

std::vector<Coverage> interval_coverage(const sim::Scenario& scenario, const sim::RigConfig& rig,
                                        const sim::GyroConfig& gyro, const CoverageOptions& options,
                                        const std::vector<CoverageMethod>& methods) {
  const auto terms = fit::parse_formula(options.model);
  Coverage blank;
  blank.seeds = options.seeds;
  std::vector<std::size_t> index;
  for (std::size_t j = 0; j < terms.size(); ++j) {
    const auto it = gyro.coefficient.find(std::string(terms[j]->name));
    if (it == gyro.coefficient.end() || it->second == 0.0) continue;
    blank.terms.push_back({std::string(terms[j]->name), it->second});
    index.push_back(j);
  }
  std::vector<Coverage> out(methods.size(), blank);
  std::vector<std::vector<double>> sum(methods.size(), std::vector<double>(index.size(), 0.0)), sum2 = sum;
  for (int s = 0; s < options.seeds; ++s) {
    sim::Scenario sc = scenario;
    sc.seed = options.first_seed + static_cast<std::uint64_t>(s);
    const fit::Measurement m = measurement_of(sim::Simulator(sc, rig, gyro).run(), scenario.name);
    // The record prepared once per sensor time constant the methods use.
    std::map<double, fit::PreparedData> prepared;
    for (std::size_t i = 0; i < methods.size(); ++i) {
      auto it = prepared.find(methods[i].sensor_tau_s);
      if (it == prepared.end()) {
        fit::PipelineOptions pipeline;
        pipeline.sensor_tau_s = methods[i].sensor_tau_s;
        it = prepared.emplace(methods[i].sensor_tau_s, fit::prepare_data(m, pipeline)).first;
      }
      const fit::PreparedData& data = it->second;
      fit::EngineSettings settings;
      if (!methods[i].intervals.empty()) settings.options["intervals"] = methods[i].intervals;
      const fit::ModelFit f = fit::fit_model(data, terms, fit::find_engine(methods[i].engine), settings);
      for (std::size_t k = 0; k < index.size(); ++k) {
        TermCoverage& t = out[i].terms[k];
        const fit::Interval& iv = f.engine.inference.intervals[index[k]];
        t.covered += iv.lower <= t.truth && t.truth <= iv.upper;
        const double err = f.coefficients.b[index[k]] / t.truth - 1.0;
        sum[i][k] += err;
        sum2[i][k] += err * err;
        t.half_width += 0.5 * (iv.upper - iv.lower) / std::abs(t.truth) / options.seeds;
      }
    }
  }
  for (std::size_t i = 0; i < methods.size(); ++i)
    for (std::size_t k = 0; k < index.size(); ++k) {
      TermCoverage& t = out[i].terms[k];
      t.bias = sum[i][k] / options.seeds;
      t.sd = std::sqrt(std::max(0.0, sum2[i][k] / options.seeds - t.bias * t.bias));
    }
  return out;
}

}  // namespace gyrotherm::studies
