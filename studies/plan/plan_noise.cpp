// The gyro's noise for `gyrotherm plan`: from a gyro file, from a JSON's
// noise_model, and back to a gyro file's [noise] (studies/plan/plan_noise.h).
#include "studies/plan/plan_noise.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "sim/noise.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"
#include "sim/util/json_fields.h"

namespace gyrotherm::studies::plan {

namespace {

using fit::kFlicker;
using fit::kGaussMarkov;
using fit::kRandomWalk;
using fit::kWhite;
using Json = nlohmann::json;

// A flicker bank (correlation times τ_i, log-spaced) and the common variance
// s² ((°/h)²) the simulator gives it for an Allan floor `floor_dph` at sample
// interval Δt: sim::GyroNoise's own normalisation (the peak of the bank's
// Allan deviation over τ ≥ Δt), so that a bank written to a gyro file draws
// exactly the variance planned with.
struct Bank {
  std::vector<double> tau_s;
  double variance_dph2 = 0;
};
Bank simulator_bank(double floor_dph, double tau_min_s, double tau_max_s, int processes, double sample_interval_s) {
  sim::NoiseConfig flicker;
  flicker.bias_instability_dph = floor_dph;
  flicker.flicker_tau_min_s = tau_min_s;
  flicker.flicker_tau_max_s = tau_max_s;
  flicker.flicker_processes = processes;
  const sim::GyroNoise noise(flicker, sample_interval_s, 0);
  return {noise.flicker_correlation_times_s(), noise.flicker_variance_dph2()};
}

// The bank's Allan floor per unit s (B/s = √ of the peak of the unit-variance
// bank's Allan variance), as the simulator finds it at Δt = 1 s. One process
// peaks at τ ≈ 1.9 τ_i, so a sample interval up to 1.9 τ_min gives the same
// (within the simulator's grid, 1e-5); a longer one cuts the peak off.
double floor_per_s(const std::vector<double>& tau_s) {
  return 1.0 / std::sqrt(simulator_bank(1.0, tau_s.front(), tau_s.back(), static_cast<int>(tau_s.size()), 1.0)
                             .variance_dph2);
}

// fit::NoiseModel::parameters() reports a component with identified = false
// as a bound ("< x, not pinned down"); a model given, not estimated, is known:
// every component that is there is identified (its interval of zero width).
void mark_present(fit::NoiseModel& m) {
  for (int k = 0; k < fit::kNoiseKinds; ++k) {
    const auto i = static_cast<std::size_t>(k);
    m.present[i] = m.amplitude[i] > 0.0 && (k != kFlicker || !m.flicker_tau_s.empty()) &&
                   (k != kGaussMarkov || m.gm_tau_s > 0.0);
    m.identified[i] = m.present[i];
  }
}

// "1.5e-04", "2e-04": one decimal of the mantissa, none when it is 0.
std::string short_e(double v) {
  std::string text = fmt::format("{:.1e}", v);
  if (const std::size_t dot = text.find(".0e"); dot != std::string::npos) text.erase(dot, 2);
  return text;
}

// A number for a gyro file, to 15 significant digits: √((60 N)²)/60, the
// bank's (B/s)·s and exp(ln τ) come back an ulp or so off the value they were
// made from, and 999999.99999999988 in a file reads as another number than 1e6.
double rounded(double v) { return std::strtod(fmt::format("{:.15g}", v).c_str(), nullptr); }

std::string shown(const Json& v) {
  std::string text = v.dump();
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

// A noise_model's components: each {"value": a number >= 0, …} in its unit,
// an absent one 0.
struct NoiseComponents {
  double arw = 0.0;               // °/√h
  double bias_instability = 0.0;  // °/h
  double gauss_markov = 0.0;      // °/h
  double gauss_markov_tau = 0.0;  // s
  double rrw = 0.0;               // °/h/√h
};

void from_json(const Json& j, NoiseComponents& c) {
  if (!j.is_object())
    throw InputError("expected an object {arw, bias_instability, gauss_markov, gauss_markov_tau, rrw}");
  const auto read = [&j](const char* name, const char* unit, double& out) {
    if (!j.contains(name)) return;
    const Json& v = j[name];
    if (!v.is_object() || !v.contains("value"))
      throw InputError(fmt::format("{} = {}: expected {{\"value\": a number >= 0 in {}, ...}}", name, shown(v), unit));
    const Json& x = v["value"];
    if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < 0.0)
      throw InputError(fmt::format("{}.value = {}: expected a number >= 0 ({})", name, shown(x), unit));
    out = x.get<double>();
  };
  read("arw", "°/√h", c.arw);
  read("bias_instability", "°/h", c.bias_instability);
  read("gauss_markov", "°/h", c.gauss_markov);
  read("gauss_markov_tau", "s", c.gauss_markov_tau);
  read("rrw", "°/h/√h", c.rrw);
}

// Reads a JSON's noise_model (plan_noise.h): where it is, and its components.
class NoiseModelReader {
 public:
  explicit NoiseModelReader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void refuse(std::string_view message) const {
    throw InputError(fmt::format("{}: {}", file_.string(), message));
  }

  Json parse() const {
    std::error_code error;
    if (!std::filesystem::exists(file_, error))
      refuse("no such file (expected the JSON of gyrotherm fit, diagnose or allan with --json)");
    if (std::filesystem::is_directory(file_, error)) refuse("is a folder, expected a JSON file");
    std::ifstream in(file_, std::ios::binary);
    if (!in) refuse("cannot be read");
    std::stringstream text;
    text << in.rdbuf();
    try {
      return Json::parse(text.str());
    } catch (const Json::exception& e) {
      refuse(fmt::format("not valid JSON ({}); expected the output of fit, diagnose or allan with --json", e.what()));
    }
  }

  // The noise_model object of fit/diagnose --json, or of allan --json's
  // series (compensated, else raw, else the first). Sets path_ and source_.
  const Json& locate(const Json& root) {
    if (!root.is_object())
      refuse(fmt::format("expected a JSON object (found {})", shown(root)));
    const Json* first = root.contains("channels") && root["channels"].is_array() && !root["channels"].empty()
                            ? &root["channels"][0]
                            : &root;
    if (first->contains("sensor") && (*first)["sensor"] != "gyro")
      refuse(fmt::format("the fit of a sensor of kind {} (its \"sensor\"): plan designs a gyro's test only, so far",
                         (*first)["sensor"].dump()));
    if (root.contains("channels")) {
      const Json& channels = root["channels"];
      std::string names;
      if (channels.is_array())
        for (const Json& c : channels)
          if (c.is_object() && c.contains("channel") && c["channel"].is_string())
            names += (names.empty() ? "" : ", ") + c["channel"].get<std::string>();
      refuse(fmt::format("holds {} ({}): plan needs one gyro's noise_model; write the JSON of one channel "
                         "(--gyro-col NAME)",
                         counted(channels.is_array() ? channels.size() : 0, "channel"), names));
    }
    if (root.contains("noise_model")) {
      path_ = "noise_model";
      source_ = fmt::format("noise_model of {}", file_.string());
      return object(root["noise_model"], "the record was too short to identify its noise");
    }
    if (root.contains("series")) {
      const Json& series = root["series"];
      if (!series.is_array() || series.empty())
        refuse(fmt::format("series: expected the list of Allan series of allan --json (found {})", shown(series)));
      std::size_t pick = 0;
      for (const char* wanted : {"raw", "compensated"})  // the later wins
        for (std::size_t i = 0; i < series.size(); ++i)
          if (series[i].is_object() && series[i].value("name", Json()) == wanted) pick = i;
      const Json& chosen = series[pick];
      const std::string name = chosen.is_object() && chosen.value("name", Json()).is_string()
                                   ? chosen["name"].get<std::string>()
                                   : std::string("unnamed");
      path_ = fmt::format("series[{}].noise_model", pick);
      source_ = fmt::format("series '{}' noise_model of {}", name, file_.string());
      if (!chosen.is_object() || !chosen.contains("noise_model"))
        refuse(fmt::format("{}: missing (series '{}' has no noise model)", path_, name));
      return object(chosen["noise_model"], fmt::format("series '{}' was too short to identify its noise", name));
    }
    refuse("no noise_model: expected the JSON of fit --json or diagnose --json (noise_model) or of allan --json "
           "(series[].noise_model); a record too short to identify its noise has none");
  }

  // The model's components (from_json below), an error inside named by its
  // path from the file's top ("noise_model.components.arw.value = …").
  NoiseComponents components(const Json& model) const {
    NoiseComponents c;
    try {
      json_fields::read_object(model, "components",
                               "an object {arw, bias_instability, gauss_markov, gauss_markov_tau, rrw}", c);
    } catch (const InputError& e) {
      refuse(json_fields::inside(path_, e).what());
    }
    return c;
  }

  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }

 private:
  const Json& object(const Json& model, const std::string& why_null) const {
    if (model.is_null()) refuse(fmt::format("{} is null: {}; nothing to plan against", path_, why_null));
    if (!model.is_object()) refuse(fmt::format("{}: expected an object (found {})", path_, shown(model)));
    return model;
  }

  std::filesystem::path file_;
  std::string path_, source_;
};

}  // namespace

PlanNoise noise_of_gyro(const sim::NoiseConfig& noise, double sample_interval_s, std::string source) {
  PlanNoise out;
  out.source = std::move(source);
  fit::NoiseModel& m = out.model;
  // White: per-sample std 60 N/√Δt, so q_w = σ²Δt = (60 N)² (°/h)²·s at any Δt.
  m.amplitude[kWhite] = std::pow(60.0 * noise.arw_deg_per_sqrt_h, 2);
  // Flicker: the simulator's own bank (its τ_i and the s² it normalised to B).
  if (noise.bias_instability_dph > 0.0) {
    const sim::GyroNoise simulated(noise, sample_interval_s, 0);
    m.flicker_tau_s = simulated.flicker_correlation_times_s();
    m.amplitude[kFlicker] = simulated.flicker_variance_dph2();
    m.flicker_floor_per_s = noise.bias_instability_dph / std::sqrt(m.amplitude[kFlicker]);
  }
  // Rate random walk: steps of K √(Δt/3600) per sample, q_r = K²/3600 (°/h)²/s.
  m.amplitude[kRandomWalk] = noise.rrw_dph_per_sqrt_h * noise.rrw_dph_per_sqrt_h / 3600.0;
  mark_present(m);
  out.arw_temp_ref_c = noise.arw_temp_ref_c;
  out.arw_temp_coeff_per_c2 = noise.arw_temp_coeff_per_c2;
  return out;
}

PlanNoise noise_of_json(const std::filesystem::path& file) {
  NoiseModelReader reader(file);
  const Json root = reader.parse();
  const Json& json = reader.locate(root);
  const NoiseComponents c = reader.components(json);
  const double arw = c.arw, floor = c.bias_instability, gm = c.gauss_markov, rrw = c.rrw;
  const double gm_tau = gm > 0.0 ? c.gauss_markov_tau : 0.0;
  if (gm > 0.0) {
    if (!(gm_tau > 0.0))
      reader.refuse(fmt::format("{}.components.gauss_markov_tau.value: expected the correlation time (s, > 0) of "
                                "gauss_markov = {} °/h",
                                reader.path(), gm));
  }
  if (arw == 0.0 && floor == 0.0 && gm == 0.0 && rrw == 0.0)
    throw InputError(fmt::format("the noise model of {} has no component: nothing to plan against", file.string()));

  PlanNoise out;
  out.source = reader.source();
  fit::NoiseModel& m = out.model;
  m.amplitude[kWhite] = std::pow(60.0 * arw, 2);
  if (floor > 0.0) {
    // 1/f between kJsonFlickerMinS and kJsonFlickerMaxS: two processes per
    // decade (Barnes 1966), their s² set so the bank's Allan floor is B.
    const int processes =
        static_cast<int>(std::lround(2.0 * std::log10(kJsonFlickerMaxS / kJsonFlickerMinS))) + 1;
    const Bank bank = simulator_bank(floor, kJsonFlickerMinS, kJsonFlickerMaxS, processes, 1.0);
    m.flicker_tau_s = bank.tau_s;
    m.amplitude[kFlicker] = bank.variance_dph2;
    m.flicker_floor_per_s = floor / std::sqrt(bank.variance_dph2);
  }
  m.amplitude[kGaussMarkov] = gm * gm;
  m.gm_tau_s = gm_tau;
  m.amplitude[kRandomWalk] = rrw * rrw / 3600.0;
  mark_present(m);
  out.arw_temp_coeff_per_c2 = 0.0;  // a(T) = 1: the JSON has one white level
  return out;
}

std::string PlanNoise::description() const {
  const fit::NoiseModel& m = model;
  std::vector<std::string> parts;
  if (m.present[kWhite])
    parts.push_back(fmt::format("white N = {:.1e} °/√h", std::sqrt(m.amplitude[kWhite]) / 60.0));
  else
    parts.emplace_back("no white noise");
  if (m.present[kFlicker]) {
    const std::vector<double>& tau = m.flicker_tau_s;
    const std::string bank = tau.size() == 1 ? fmt::format("1 process at {:g} s", tau.front())
                                             : fmt::format("{} processes {:g}..{:g} s", tau.size(), tau.front(),
                                                           tau.back());
    parts.push_back(fmt::format("flicker B = {:.1e} °/h ({})", m.flicker_floor_per_s * std::sqrt(m.amplitude[kFlicker]),
                                bank));
  } else {
    parts.emplace_back("no flicker");
  }
  if (m.present[kGaussMarkov])
    parts.push_back(fmt::format("Gauss–Markov σ = {:.1e} °/h, τ = {} s", std::sqrt(m.amplitude[kGaussMarkov]),
                                human(m.gm_tau_s)));
  if (m.present[kRandomWalk])
    parts.push_back(fmt::format("random walk K = {:.1e} °/h/√h", std::sqrt(m.amplitude[kRandomWalk] * 3600.0)));
  else
    parts.emplace_back("no random walk");
  if (arw_temp_coeff_per_c2 != 0.0 && m.present[kWhite])
    parts.push_back(fmt::format("white ×(1 + {}·(T − {:g} °C)²)", short_e(arw_temp_coeff_per_c2), arw_temp_ref_c));
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : ", ") + part;
  return text;
}

sim::NoiseConfig noise_config_of(const PlanNoise& noise, const sim::NoiseConfig& base, bool from_gyro_file,
                                 std::optional<GaussMarkovMerged>* merged) {
  if (merged != nullptr) merged->reset();
  if (from_gyro_file) return base;  // the gyro's own, quantisation and glitches included
  const fit::NoiseModel& m = noise.model;
  sim::NoiseConfig out;  // the bank's τ range and count: the defaults when there is none
  out.arw_deg_per_sqrt_h = rounded(std::sqrt(m.amplitude[kWhite]) / 60.0);
  out.rrw_dph_per_sqrt_h = rounded(std::sqrt(m.amplitude[kRandomWalk] * 3600.0));
  out.quantization_arcsec = 0.0;
  out.glitch_rate_per_h = 0.0;
  out.arw_temp_ref_c = noise.arw_temp_ref_c;
  out.arw_temp_coeff_per_c2 = noise.arw_temp_coeff_per_c2;
  out.bias_instability_dph = 0.0;
  const bool flicker = m.present[kFlicker], gauss_markov = m.present[kGaussMarkov];
  if (flicker) {
    // The bank as the simulator builds it (log-spaced from the first τ_i to
    // the last); a Gauss–Markov process beside it cannot be written (a gyro
    // file has one bank), so its variance σ² is spread over the M processes:
    // the total variance and the bank's span are kept, its correlation time
    // is not.
    const double processes = static_cast<double>(m.flicker_tau_s.size());
    const double variance = m.amplitude[kFlicker] + (gauss_markov ? m.amplitude[kGaussMarkov] / processes : 0.0);
    out.flicker_tau_min_s = rounded(m.flicker_tau_s.front());
    out.flicker_tau_max_s = rounded(m.flicker_tau_s.back());
    out.flicker_processes = static_cast<int>(m.flicker_tau_s.size());
    out.bias_instability_dph = rounded(std::sqrt(variance) * floor_per_s(m.flicker_tau_s));
    if (gauss_markov && merged != nullptr)
      *merged = GaussMarkovMerged{std::sqrt(m.amplitude[kGaussMarkov]), m.gm_tau_s,
                                  std::sqrt(m.amplitude[kFlicker]) * m.flicker_floor_per_s, out.bias_instability_dph,
                                  out.flicker_processes, out.flicker_tau_min_s, out.flicker_tau_max_s};
  } else if (gauss_markov) {
    // One process at τ_c: the simulator sets s² = B²/peak, so B = σ·√peak.
    out.flicker_tau_min_s = out.flicker_tau_max_s = m.gm_tau_s;
    out.flicker_processes = 1;
    out.bias_instability_dph = rounded(std::sqrt(m.amplitude[kGaussMarkov]) * floor_per_s({m.gm_tau_s}));
  }
  return out;
}

}  // namespace gyrotherm::studies::plan
