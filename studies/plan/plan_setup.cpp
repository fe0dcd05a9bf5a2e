#include "studies/plan/plan_setup.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <optional>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "fit/model/formula.h"
#include "sim/config_loader.h"
#include "sim/util/input_error.h"
#include "sim/util/numbers.h"

namespace gyrotherm::studies::plan {

namespace {


double number_of(const std::string& text, const std::string& option) {
  double v = 0.0;
  std::size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw InputError(fmt::format("{}: '{}' is not a number", option, text));
  return v;
}

// "NAME=VALUE" → (NAME, VALUE); `value_optional`: "NAME" alone gives NaN.
std::pair<std::string, double> name_value(const std::string& item, const std::string& option,
                                          bool value_optional = false) {
  const auto eq = item.find('=');
  if (eq == std::string::npos) {
    if (value_optional) return {item, std::nan("")};
    throw InputError(fmt::format("{}: expected NAME=VALUE, got '{}'", option, item));
  }
  return {item.substr(0, eq), number_of(item.substr(eq + 1), option + " " + item.substr(0, eq))};
}

nlohmann::ordered_json read_json(const std::filesystem::path& file, const std::string& option) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{} {}: cannot open the file", option, file.string()));
  try {
    return nlohmann::ordered_json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{} {}: not valid JSON ({})", option, file.string(), e.what()));
  }
}

std::size_t index_of(const PlanModel& m, std::string_view name) {
  for (std::size_t j = 0; j < m.terms.size(); ++j)
    if (m.terms[j]->name == name) return j;
  return m.terms.size();
}

void add_term(PlanModel& m, const fit::Term* t) {
  if (index_of(m, t->name) < m.terms.size()) return;
  m.terms.push_back(t);
  m.parameters.push_back(std::nan(""));
  m.prior.push_back(0.0);
}

const fit::Term* term_named(const std::string& name, const std::string& option) {
  const fit::Term* t = fit::term_by_name(name);
  if (!t) throw InputError(fmt::format("{}: unknown term '{}' (terms: {})", option, name, fit::term_list()));
  return t;
}

// Set points of a scenario, for the default range and rate.
void scenario_limits(const sim::Scenario& s, RigLimits& limits, bool want_range, bool want_rate) {
  double lo = s.start_c, hi = s.start_c, rate = 0.0;
  for (const sim::Segment& seg : s.segments) {
    if (seg.kind == sim::SegmentKind::free) continue;
    lo = std::min(lo, seg.temp_c);
    hi = std::max(hi, seg.temp_c);
    if (seg.kind == sim::SegmentKind::ramp) rate = std::max(rate, seg.rate_c_per_min);
  }
  if (want_range) {
    if (!(hi > lo))
      throw InputError(fmt::format("{} holds one temperature: give the chamber's range with --range LO,HI",
                                   s.file.filename().string()));
    limits.low_c = lo;
    limits.high_c = hi;
  }
  if (want_rate) {
    if (!(rate > 0.0))
      throw InputError(fmt::format("{} has no ramp: give the chamber's rate limit with --max-rate",
                                   s.file.filename().string()));
    limits.max_rate_c_per_min = rate;
  }
}

// --out: checked before the search (which takes seconds to minutes).
void check_out_folder(const std::string& out_option) {
  std::error_code ec;
  const std::filesystem::path out = out_option;
  if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec))
    throw InputError(fmt::format("--out {}: is a file, not a folder", out_option));
  // The nearest folder that exists must be one, and writable.
  std::filesystem::path up = out.empty() ? std::filesystem::path(".") : out;
  while (!up.empty() && !std::filesystem::exists(up, ec)) up = up.parent_path();
  if (up.empty()) up = ".";
  if (!std::filesystem::is_directory(up, ec) || ::access(up.c_str(), W_OK) != 0)
    throw InputError(fmt::format("--out {}: {} is not a folder this user can write in", out_option, up.string()));
  for (const char* name : {"plan.toml", "rig.toml", "gyro.toml", "plan_setpoint.csv", "plan.png"})
    if (std::filesystem::exists(out / name, ec) && !std::filesystem::is_regular_file(out / name, ec))
      throw InputError(fmt::format("--out {}: {} is there and not a file", out_option, name));
}

// A diagnose --json given to --separate: its `plan` (the verdict's group,
// each member's size and parameter, the model, the record's range) and its
// noise, each where the options do not say otherwise.
std::optional<nlohmann::ordered_json> read_diagnosis(const PlanRequest& rq) {
  std::optional<nlohmann::ordered_json> diagnosis;
  if (rq.separate.size() == 1 && rq.separate[0].ends_with(".json")) {
    diagnosis = read_json(rq.separate[0], "--separate");
    const nlohmann::ordered_json& d = *diagnosis;
    if (!d.contains("plan") || !d["plan"].is_object() || !d["plan"].contains("separate"))
      throw InputError(fmt::format("--separate {}: the diagnosis suggests no test ('plan' is absent: no group "
                                   "of effects it could not tell apart passed its test); name the terms: "
                                   "--separate A=SIZE,B=SIZE",
                                   rq.separate[0]));
  }
  return diagnosis;
}

// The rig's limits (a diagnosis's range, its record's, where --range is not
// given), the start clamped into them, and the thermal path.
void set_limits(const PlanRequest& rq, const std::optional<nlohmann::ordered_json>& diagnosis,
                const std::filesystem::path& rig_file, PlanSetup& s) {
  std::optional<std::pair<double, double>> range = rq.range_c;
  if (!range && diagnosis) {
    const nlohmann::ordered_json& d = *diagnosis;
    // A range the diagnosis says cannot separate the group is not taken: the scenario's set points are.
    if (d["plan"].value("range_separates", true) && d["plan"].contains("range_c") && d["plan"]["range_c"].is_array() &&
        d["plan"]["range_c"].size() == 2 && d["plan"]["range_c"][0].is_number() && d["plan"]["range_c"][1].is_number())
      range = std::pair{d["plan"]["range_c"][0].get<double>(), d["plan"]["range_c"][1].get<double>()};
  }
  scenario_limits(s.base, s.limits, !range, !rq.max_rate_c_per_min);
  if (range) {
    s.limits.low_c = range->first;
    s.limits.high_c = range->second;
    if (!(s.limits.high_c > s.limits.low_c))
      throw InputError(fmt::format("--range {},{}: the low end must be below the high end", s.limits.low_c,
                                   s.limits.high_c));
  }
  if (s.limits.low_c < s.rig.chamber.min_c || s.limits.high_c > s.rig.chamber.max_c)
    throw InputError(fmt::format("--range {},{} is outside the chamber's working range {}..{} °C ({})",
                                 s.limits.low_c, s.limits.high_c, s.rig.chamber.min_c, s.rig.chamber.max_c,
                                 rig_file.filename().string()));
  // The single options' ranges (--max-rate > 0, --longest <= 720 h, …) are
  // their rows' rules (studies/options/plan_options.cpp).
  if (rq.max_rate_c_per_min) s.limits.max_rate_c_per_min = *rq.max_rate_c_per_min;
  if (rq.longest_h * 3600.0 < 800.0)
    throw InputError(fmt::format("--longest {} h: a test needs at least 8 windows of 100 s (0.23 h)", rq.longest_h));
  if (rq.min_soak_s >= rq.longest_h * 3600.0)
    throw InputError(fmt::format("--min-soak {} s is not shorter than --longest {} h: a soak would fill the whole "
                                 "test; give a shorter --min-soak (0 allows turning at once)",
                                 rq.min_soak_s, rq.longest_h));
  s.limits.min_soak_s = rq.min_soak_s;
  s.limits.longest_s = rq.longest_h * 3600.0;
  s.limits.start_c = std::clamp(s.base.start_c, s.limits.low_c, s.limits.high_c);
  if (s.limits.start_c != s.base.start_c)
    s.notes.emplace_back(StartClamped{s.base.start_c, s.limits.start_c});
  s.base.start_c = s.limits.start_c;
  s.base.initial = sim::InitialCondition::soaked;
  if (rq.tau_s) {
    s.rig = first_order_rig(*rq.tau_s, s.rig);
    s.thermal_path.tau_s = *rq.tau_s;
  } else {
    s.thermal_path.rig_file = rig_file.filename().string();
    s.thermal_path.scenario_file = std::filesystem::path(rq.scenario).filename().string();
  }
}

// The terms to tell apart, with their sizes, and what a diagnosis brings.
struct SeparateGroup {
  std::size_t model_terms = 0;  // the model's own, before the group's are added
  std::vector<std::string> names;
  std::vector<double> sizes;
  std::string noise_file;
  std::vector<std::pair<std::string, double>> json_params;
};

// The model (--model, a diagnosis's, or the default) and the group to separate.
SeparateGroup set_model(const PlanRequest& rq, const std::optional<nlohmann::ordered_json>& diagnosis, PlanSetup& s) {
  std::string model_text = rq.model.empty() ? std::string(fit::kDefaultModel) : rq.model;
  if (rq.model.empty() && diagnosis && (*diagnosis)["plan"].contains("model") &&
      (*diagnosis)["plan"]["model"].is_string())
    model_text = (*diagnosis)["plan"]["model"].get<std::string>();
  s.model_text = model_text;
  for (const fit::Term* t : fit::parse_formula(model_text)) {
    if (fit::is_column_term(t))
      throw InputError(fmt::format("--model: '{}' is a column of a log; a planned test has the simulator's "
                                   "temperatures only (T, T2 and what is made from them)",
                                   t->name));
    add_term(s.model, t);
  }
  SeparateGroup g;
  g.model_terms = s.model.terms.size();
  g.noise_file = rq.noise;
  if (diagnosis) {
    const nlohmann::ordered_json& d = *diagnosis;
    for (const auto& [name, size] : d["plan"]["separate"].items()) {
      g.names.push_back(name);
      g.sizes.push_back(size.is_number() ? size.get<double>() : std::nan(""));
    }
    if (d["plan"].contains("param"))
      for (const auto& [name, value] : d["plan"]["param"].items())
        if (value.is_number()) g.json_params.emplace_back(name, value.get<double>());
    if (g.noise_file.empty() && d.contains("noise_model")) g.noise_file = rq.separate[0];
  } else {
    for (const std::string& item : rq.separate) {
      const auto [name, size] = name_value(item, "--separate", true);
      g.names.push_back(name);
      g.sizes.push_back(size);
    }
  }
  if (!rq.separate.empty() && g.names.size() < 2 && g.model_terms == 0)
    throw InputError("--separate: name at least two terms to tell apart");
  for (const std::string& name : g.names) add_term(s.model, term_named(name, "--separate"));
  return g;
}

// Priors: the gyro's truth, a fit JSON's coefficients, --separate's sizes,
// --prior; the noise; the parameters.
void set_priors_and_noise(const PlanRequest& rq, const std::optional<nlohmann::ordered_json>& diagnosis,
                          const std::filesystem::path& gyro_file, const SeparateGroup& g, PlanSetup& s) {
  for (std::size_t j = 0; j < s.model.terms.size(); ++j) {
    const fit::Term* t = s.model.terms[j];
    if (t->effect) {
      s.model.prior[j] = s.gyro.coefficient_of(*t->effect);
      if (t->parameter) s.model.parameters[j] = s.gyro.parameter_of(*t->effect);
    } else if (t->parameter) {
      s.model.parameters[j] = fit::default_parameters({t})[0];
    }
  }
  s.noise_from_gyro_file = g.noise_file.empty();
  if (!g.noise_file.empty()) {
    s.noise = noise_of_json(g.noise_file);
    const nlohmann::ordered_json j =
        diagnosis && g.noise_file == rq.separate[0] ? *diagnosis : read_json(g.noise_file, "--noise");
    // Components the record could not pin down are used at their estimate;
    // their bound says how much worse the noise could be.
    if (j.contains("noise_model") && j["noise_model"].is_object() && j["noise_model"].contains("components")) {
      LooseNoise loose{std::filesystem::path(g.noise_file).filename().string(), {}};
      for (const auto& [name, c] : j["noise_model"]["components"].items())
        if (c.is_object() && c.value("identified", true) == false && c.contains("interval_95") &&
            c["interval_95"].is_array() && c["interval_95"].size() == 2 && c["interval_95"][1].is_number() &&
            c["interval_95"][1].get<double>() > 0.0)
          loose.components.push_back({name, c.value("unit", ""), c["interval_95"][1].get<double>()});
      if (!loose.components.empty()) s.notes.emplace_back(std::move(loose));
    }
    if (j.contains("coefficients") && j["coefficients"].is_object())
      for (std::size_t k = 0; k < s.model.terms.size(); ++k) {
        const std::string name(s.model.terms[k]->name);
        if (j["coefficients"].contains(name) && j["coefficients"][name].is_number())
          s.model.prior[k] = j["coefficients"][name].get<double>();
        if (s.model.terms[k]->parameter && j.contains("parameters") && j["parameters"].contains(name))
          for (const auto& [key, v] : j["parameters"][name].items())
            if (v.is_number()) s.model.parameters[k] = v.get<double>();
      }
    std::optional<GaussMarkovMerged> merged;
    s.gyro.noise = noise_config_of(s.noise, s.gyro.noise, false, &merged);
    if (merged) s.notes.emplace_back(*merged);
  } else {
    s.noise = noise_of_gyro(s.gyro.noise, 1.0 / s.base.sample_rate_hz, "gyro file " + gyro_file.filename().string());
  }
  for (std::size_t k = 0; k < g.names.size(); ++k)
    if (std::isfinite(g.sizes[k])) s.model.prior[index_of(s.model, g.names[k])] = g.sizes[k];
  for (const std::string& item : rq.prior) {
    const auto [name, value] = name_value(item, "--prior");
    const std::size_t k = index_of(s.model, name);
    if (k == s.model.terms.size()) throw InputError(fmt::format("--prior {}: {} is not in the model", item, name));
    s.model.prior[k] = value;
  }
  std::vector<std::pair<std::string, double>> params = g.json_params;
  for (const std::string& item : rq.param) params.push_back(name_value(item, "--param"));
  for (const auto& [name, value] : params) {
    const std::string item = fmt::format("{}={:g}", name, value);
    const std::size_t k = index_of(s.model, name);
    if (k == s.model.terms.size() || !s.model.terms[k]->parameter)
      throw InputError(fmt::format("--param {}: not a term of the model with a parameter", item));
    const auto& p = *s.model.terms[k]->parameter;
    if (!(value >= p.lower && value <= p.upper))
      throw InputError(fmt::format("--param {}: {} must lie in [{:g}, {:g}]", item, p.name, p.lower, p.upper));
    s.model.parameters[k] = value;
  }
}

// The targets (--se, --rel-se, --separate, or a prior to detect) and the gyro --verify simulates.
void set_targets(const PlanRequest& rq, const SeparateGroup& g, PlanSetup& s) {
  s.terms.resize(s.model.terms.size());
  for (std::size_t j = 0; j < s.model.terms.size(); ++j) {
    TermPlan& t = s.terms[j];
    t.term = s.model.terms[j]->name;
    t.unit = s.model.terms[j]->coefficient_unit();
    t.prior = s.model.prior[j];
    t.target_se = kInfinity;
  }
  auto need_prior = [&](std::size_t j, const std::string& option) {
    if (s.model.prior[j] == 0.0)
      throw InputError(fmt::format("{}: no prior value of {}'s coefficient to take a fraction of (the gyro "
                                   "file has none, nor a --noise fit file); give --se {}=VALUE or "
                                   "--separate {}=SIZE",
                                   option, s.terms[j].term, s.terms[j].term, s.terms[j].term));
    return std::abs(s.model.prior[j]);
  };
  for (const std::string& name : g.names) {
    const std::size_t j = index_of(s.model, name);
    s.terms[j].target_se = need_prior(j, "--separate " + name) / kDetectableInSe;
    s.terms[j].target_from = TermPlan::TargetFrom::separate;
  }
  for (const std::string& item : rq.rel_se) {
    if (item.find('=') == std::string::npos) {
      const double f = number_of(item, "--rel-se");
      if (!(f > 0.0)) throw InputError(fmt::format("--rel-se {}: must be > 0", item));
      for (std::size_t j = 0; j < g.model_terms; ++j)
        if (s.model.prior[j] != 0.0) {
          s.terms[j].target_se = f * std::abs(s.model.prior[j]);
          s.terms[j].target_from = TermPlan::TargetFrom::rel_se;
          s.terms[j].rel_se_given = item;
        }
      continue;
    }
    const auto [name, f] = name_value(item, "--rel-se");
    const std::size_t j = index_of(s.model, name);
    if (j == s.model.terms.size()) throw InputError(fmt::format("--rel-se {}: {} is not in the model", item, name));
    if (!(f > 0.0)) throw InputError(fmt::format("--rel-se {}: must be > 0", item));
    s.terms[j].target_se = f * need_prior(j, "--rel-se " + item);
    s.terms[j].target_from = TermPlan::TargetFrom::rel_se;
    s.terms[j].rel_se_given = item;
  }
  for (const std::string& item : rq.se) {
    const auto [name, v] = name_value(item, "--se");
    const std::size_t j = index_of(s.model, name);
    if (j == s.model.terms.size()) throw InputError(fmt::format("--se {}: {} is not in the model", item, name));
    if (!(v > 0.0)) throw InputError(fmt::format("--se {}: must be > 0 (in {})", item, s.terms[j].unit));
    s.terms[j].target_se = v;
    s.terms[j].target_from = TermPlan::TargetFrom::se;
  }
  if (rq.se.empty() && rq.rel_se.empty() && rq.separate.empty())
    for (std::size_t j = 0; j < g.model_terms; ++j)
      if (s.model.prior[j] != 0.0 && !std::isfinite(s.terms[j].target_se)) {
        s.terms[j].target_se = std::abs(s.model.prior[j]) / kDetectableInSe;
        s.terms[j].target_from = TermPlan::TargetFrom::detect;
      }
  if (std::none_of(s.terms.begin(), s.terms.end(), [](const TermPlan& t) { return std::isfinite(t.target_se); }))
    throw InputError("no precision to plan for: no term has a prior value to detect; give --se TERM=VALUE");
  for (std::size_t j = 0; j < s.model.terms.size(); ++j)
    if (s.model.terms[j]->parameter && s.model.prior[j] == 0.0)
      s.notes.emplace_back(ParameterAssumed{s.terms[j].term, std::string(s.model.terms[j]->parameter->name),
                                            s.model.parameters[j]});
  // The gyro --verify simulates: priors as the truth where the gyro had none.
  for (std::size_t j = 0; j < s.model.terms.size(); ++j)
    if (s.model.terms[j]->effect && s.model.prior[j] != 0.0) {
      s.gyro.coefficient[std::string(s.model.terms[j]->name)] = s.model.prior[j];
      if (s.model.terms[j]->parameter && std::isfinite(s.model.parameters[j]))
        s.gyro.parameter[std::string(s.model.terms[j]->name)] = s.model.parameters[j];
    }
}

}  // namespace

sim::RigConfig first_order_rig(double tau_s, const sim::RigConfig& chamber_of) {
  sim::RigConfig r;
  r.chamber = chamber_of.chamber;
  r.sensor = chamber_of.sensor;
  r.case_.capacity_j_per_k = 1000.0;
  r.case_.convection_w_per_k = 1000.0 / tau_s;
  r.case_.natural_convection = false;
  r.case_.emissivity = 0.0;
  r.case_.area_m2 = 0.0;
  r.block.anode_capacity_j_per_k = r.block.far_capacity_j_per_k = 1.0;
  r.block.anode_far_w_per_k = 0.0;
  r.block.anode_case_w_per_k = r.block.far_case_w_per_k = 10.0;
  r.sensor.time_constant_s = 1.0;
  r.power = {0.0, 0.0, 0.0};
  return r;
}

PlanSetup plan_setup(const PlanRequest& rq) {
  PlanSetup s;
  check_out_folder(rq.out);
  if (rq.scenario.empty()) throw InputError("plan: no scenario given");
  s.base = sim::load_scenario(rq.scenario);
  const std::filesystem::path rig_file = rq.rig.empty() ? s.base.rig_file : std::filesystem::path(rq.rig);
  const std::filesystem::path gyro_file = rq.gyro.empty() ? s.base.gyro_file : std::filesystem::path(rq.gyro);
  s.rig = sim::load_rig(rig_file);
  s.gyro = sim::load_gyro(gyro_file);
  s.base.rig_file = rig_file;
  s.base.gyro_file = gyro_file;
  if (!s.base.chamber)
    throw InputError(fmt::format("{} has no chamber (chamber = false): plan designs chamber tests; use a "
                                 "scenario with a chamber, e.g. scenarios/cycle.toml",
                                 rq.scenario));
  const std::optional<nlohmann::ordered_json> diagnosis = read_diagnosis(rq);
  set_limits(rq, diagnosis, rig_file, s);
  const SeparateGroup group = set_model(rq, diagnosis, s);
  set_priors_and_noise(rq, diagnosis, gyro_file, group, s);
  set_targets(rq, group, s);
  return s;
}

}  // namespace gyrotherm::studies::plan
