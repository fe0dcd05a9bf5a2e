#include "studies/plan/plan.h"

#include <chrono>
#include <optional>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "fit/model/formula.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"
#include "studies/plan/plan_files.h"
#include "studies/plan/plan_setup.h"
#include "studies/plan/search.h"
#include "studies/plan/verify.h"

namespace gyrotherm::studies::plan {

namespace {

std::vector<double> targets_of(const std::vector<TermPlan>& terms) {
  std::vector<double> t;
  for (const TermPlan& p : terms) t.push_back(p.target_se);
  return t;
}

// "se(T^2) = 4.1e-07, 1.3 × its target 3.2e-07" for each term short of its target.
std::string shortfalls(const std::vector<TermPlan>& terms, const Precision& p) {
  std::string out;
  for (std::size_t j = 0; j < terms.size() && j < p.se.size(); ++j)
    if (std::isfinite(terms[j].target_se) && !(p.se[j] <= terms[j].target_se))
      out += fmt::format("{}se({}) = {:.3g} {}, {:.3g} × its target {:.3g}", out.empty() ? "" : "; ", terms[j].term,
                         p.se[j], terms[j].unit, p.se[j] / terms[j].target_se, terms[j].target_se);
  for (std::size_t j = 0; j < terms.size(); ++j)
    if (std::isfinite(terms[j].target_se) && j < p.log_parameter_se.size() &&
        p.log_parameter_se[j] > kLogParameterSe)
      out += fmt::format("{}{}'s parameter known to ±{:.0f} % only (a prediction needs ±{:.0f} %)",
                         out.empty() ? "" : "; ", terms[j].term, 100.0 * p.log_parameter_se[j], 100.0 * kLogParameterSe);
  return out;
}

std::string hours(double s) { return fmt::format("{:.2f} h", s / 3600.0); }

}  // namespace

std::string baseline_why(const Baseline& b, const PlanResult& r) {
  if (b.met) return {};
  if (b.closest.refused()) return refusal_text(b.closest);
  if (b.too_long) return fmt::format("longer than --longest ({})", hours(r.limits.longest_s));
  return shortfalls(r.terms, b.closest);
}

std::string target_from_text(const TermPlan& t) {
  switch (t.target_from) {
    case TermPlan::TargetFrom::none: return {};
    case TermPlan::TargetFrom::se: return "--se";
    case TermPlan::TargetFrom::rel_se: return "--rel-se " + t.rel_se_given;
    case TermPlan::TargetFrom::separate: return "--separate (p < 0.01, 90 % power)";
    case TermPlan::TargetFrom::detect: return "detect (p < 0.01, 90 % power)";
  }
  return {};
}

std::string noise_text(const PlanNoise& noise) { return noise.description() + " (" + noise.source + ")"; }

PlanResult run_plan(const PlanRequest& request, const PlanProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  auto report = [&](const std::string& stage, int done, int total) {
    if (progress.report) progress.report(stage, done, total);
  };
  if (request.verify < 0 || request.verify == 1 || request.verify > 100000)
    throw InputError(fmt::format("--verify {}: give the number of simulated tests, 2..100000 (0: none)",
                                 request.verify));
  PlanSetup setup = plan_setup(request);
  PlanResult r;
  r.request = request;
  r.terms = setup.terms;
  r.model = fit::formula_text(setup.model.terms);
  r.limits = setup.limits;
  r.thermal_path = setup.thermal_path;
  r.noise = setup.noise;
  r.notes = setup.notes;
  sim::Scenario predicted = setup.base;
  predicted.sample_rate_hz = kPredictionRateHz;
  const DesignEvaluator evaluator(predicted, setup.rig, setup.gyro, setup.noise, setup.model);
  const std::vector<double> target = targets_of(setup.terms);

  // The standard recipes at the same limits and target.
  const std::vector<Recipe> recipes = standard_recipes(setup.limits);
  std::optional<Candidate> best_recipe;  // the shortest recipe that meets the target
  std::optional<double> warmup_s;        // the warm-up's duration, where it meets the target
  std::string best_recipe_name;
  for (std::size_t i = 0; i < recipes.size(); ++i) {
    report("standard recipes", static_cast<int>(i), static_cast<int>(recipes.size()));
    const SearchOutcome o = shortest_recipe(evaluator, recipes[i], target);
    Baseline b{recipes[i].name, recipes[i].about};
    b.met = o.met;
    b.duration_s = o.best.precision.duration_s;
    b.shortfall = o.best.shortfall;
    if (!o.met) {
      b.closest = o.best.precision;
      b.too_long = !o.best.fits;
    }
    r.baselines.push_back(b);
    r.evaluations += o.evaluations;
    if (o.met && recipes[i].kind == Recipe::Kind::warmup) warmup_s = o.best.precision.duration_s;
    // The warm-up's cold soak is not counted: it is no plan for a unit that starts warm.
    if (o.met && recipes[i].kind != Recipe::Kind::warmup &&
        (!best_recipe || o.best.precision.duration_s < best_recipe->precision.duration_s)) {
      best_recipe = o.best;
      best_recipe_name = recipes[i].name;
    }
  }
  report("standard recipes", static_cast<int>(recipes.size()), static_cast<int>(recipes.size()));

  // The planned profile.
  SearchOutcome plan = shortest_plan(evaluator, setup.limits, target,
                                     [&](int done, int total) { report("planning", done, total); });
  // The search's family is not every profile: where a recipe does better, it is the plan.
  if (best_recipe && (!plan.met || best_recipe->precision.duration_s < plan.best.precision.duration_s)) {
    r.notes.emplace_back(RecipeIsPlan{best_recipe_name});
    plan.best = *best_recipe;
    plan.met = true;
  }
  r.evaluations += plan.evaluations;
  if (!plan.met) {
    const Precision& p = plan.best.precision;
    if (p.refused() || !std::isfinite(plan.best.shortfall))
      throw InputError(fmt::format(
          "the model cannot be identified at these limits by any test of at most {}: {}. The rig's thermal "
          "path ({}) over {}..{} °C at {} °C/min does not make these terms differ",
          hours(setup.limits.longest_s), p.refused() ? refusal_text(p) : "its terms do not vary apart",
          thermal_path_text(setup.thermal_path), setup.limits.low_c, setup.limits.high_c, setup.limits.max_rate_c_per_min));
    throw InputError(fmt::format(
        "no test of at most {} at these limits ({}..{} °C, {} °C/min, soaks ≥ {} s) meets the precision "
        "wanted: the closest ({}) gives {}. Under this gyro's noise ({}) a longer test does not always help "
        "(slow noise grows with the record). Relax --se/--rel-se, widen --range, raise --max-rate, or allow "
        "a longer test (--longest)",
        hours(setup.limits.longest_s), setup.limits.low_c, setup.limits.high_c, setup.limits.max_rate_c_per_min,
        setup.limits.min_soak_s, hours(p.duration_s), shortfalls(setup.terms, p), setup.noise.description()));
  }
  // A chamber is programmed in minutes: soaks rounded up to whole minutes,
  // kept if the rounded test still meets the target.
  {
    ChamberProfile minutes = plan.best.profile;
    for (sim::Segment& seg : minutes.segments)
      if (seg.kind == sim::SegmentKind::hold) seg.duration_s = 60.0 * std::ceil(seg.duration_s / 60.0 - 1e-9);
    const Candidate rounded = candidate_of(evaluator, std::move(minutes), target, setup.limits.longest_s);
    ++r.evaluations;
    if (rounded.met()) plan.best = rounded;
  }
  r.profile = plan.best.profile;
  r.duration_s = plan.best.precision.duration_s;
  r.sensor_min_c = plan.best.precision.sensor_min_c;
  r.sensor_max_c = plan.best.precision.sensor_max_c;
  r.windows = plan.best.precision.windows;
  if (warmup_s && *warmup_s < r.duration_s)
    r.notes.emplace_back(WarmupNotCounted{*warmup_s, setup.limits.low_c, setup.limits.start_c});
  for (std::size_t j = 0; j < r.terms.size(); ++j) {
    r.terms[j].predicted_se = plan.best.precision.se[j];
    r.terms[j].parameter = setup.model.parameters[j];
    r.terms[j].parameter_log_se = plan.best.precision.log_parameter_se[j];
  }

  if (request.verify > 0) {
    const auto t0 = std::chrono::steady_clock::now();
    sim::Scenario sc = setup.base;
    sc.start_c = r.profile.start_c;
    sc.segments = r.profile.segments;
    const std::uint64_t first = request.seed.value_or(setup.base.seed);
    const VerifyOutcome v = verify_plan(sc, setup.rig, setup.gyro, setup.model.terms, request.verify, first,
                                        [&](int done, int total) { report("verifying", done, total); });
    Verification out;
    out.seeds = v.seeds;
    out.first_seed = first;
    out.achieved_se = v.achieved_se;
    out.mean_reported_se = v.reported_se;
    out.coverage_95 = v.coverage_95;
    out.truth = v.truth;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.verification = out;
  }
  write_plan_files(r, setup, evaluator.detail(r.profile));
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

nlohmann::ordered_json plan_json(const PlanResult& r) {
  using Json = nlohmann::ordered_json;
  auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json j = {{"model", r.model},         {"duration_s", r.duration_s},       {"scenario_file", r.scenario_file},
            {"setpoint_file", r.setpoint_file}, {"rig_file", r.rig_file}, {"gyro_file", r.gyro_file},
            {"figure", r.figure_file}};
  Json predicted = Json::object(), target = Json::object(), prior = Json::object(), from = Json::object();
  for (const TermPlan& t : r.terms) {
    predicted[t.term] = number(t.predicted_se);
    target[t.term] = number(t.target_se);
    prior[t.term] = t.prior == 0.0 ? Json(nullptr) : Json(t.prior);
    from[t.term] = target_from_text(t);
  }
  j["predicted_se"] = predicted;
  Json parameters = Json::object();
  for (const TermPlan& t : r.terms)
    if (!std::isnan(t.parameter_log_se))
      parameters[t.term] = {{"value", t.parameter}, {"predicted_log_se", t.parameter_log_se}};
  j["parameters"] = parameters;
  j["target_se"] = target;
  j["target_from"] = from;
  j["prior"] = prior;
  Json baselines = Json::array();
  for (const Baseline& b : r.baselines)
    baselines.push_back({{"recipe", b.recipe},
                         {"duration_s", b.met ? Json(b.duration_s) : Json(nullptr)},
                         {"about", b.about},
                         {"closest_s", b.met ? Json(nullptr) : Json(b.closest.duration_s)},
                         {"shortfall", number(b.shortfall)},
                         {"why", baseline_why(b, r)}});
  j["baselines"] = baselines;
  Json segments = Json::array();
  for (const sim::Segment& s : r.profile.segments) {
    Json seg = {{"kind", sim::to_string(s.kind)}, {"temp_c", s.temp_c}};
    if (s.kind == sim::SegmentKind::ramp) seg["rate_c_per_min"] = s.rate_c_per_min;
    else seg["duration_s"] = s.duration_s;
    segments.push_back(seg);
  }
  j["profile"] = {{"start_c", r.profile.start_c}, {"segments", segments}};
  j["limits"] = {{"range_c", {r.limits.low_c, r.limits.high_c}},
                 {"max_rate_c_per_min", r.limits.max_rate_c_per_min},
                 {"min_soak_s", r.limits.min_soak_s},
                 {"longest_s", r.limits.longest_s}};
  j["thermal_path"] = thermal_path_text(r.thermal_path);
  j["noise"] = noise_text(r.noise);
  j["sensor_range_c"] = {r.sensor_min_c, r.sensor_max_c};
  j["windows"] = r.windows;
  if (r.verification) {
    const Verification& v = *r.verification;
    Json achieved = Json::object(), coverage = Json::object(), reported = Json::object(), truth = Json::object();
    for (std::size_t k = 0; k < r.terms.size(); ++k) {
      achieved[r.terms[k].term] = number(v.achieved_se[k]);
      coverage[r.terms[k].term] = number(v.coverage_95[k]);
      reported[r.terms[k].term] = number(v.mean_reported_se[k]);
      truth[r.terms[k].term] = v.truth[k];
    }
    j["achieved_se"] = achieved;
    j["coverage_95"] = coverage;
    j["reported_se"] = reported;
    j["verify"] = {{"seeds", v.seeds}, {"first_seed", v.first_seed}, {"truth", truth}, {"seconds", v.seconds}};
  }
  Json notes = Json::array();
  for (const PlanNote& n : r.notes) notes.push_back(note_text(n));
  j["notes"] = notes;
  j["evaluations"] = r.evaluations;
  j["seconds"] = r.seconds;
  return j;
}

std::string plan_text(const PlanResult& r) {
  std::string out = fmt::format("plan for B = b0 + {}\n", r.model);
  out += fmt::format("  rig: {}; chamber {}..{} °C, at most {} °C/min, soaks ≥ {} s\n", thermal_path_text(r.thermal_path),
                     r.limits.low_c, r.limits.high_c, r.limits.max_rate_c_per_min, r.limits.min_soak_s);
  out += fmt::format("  noise: {}\n\n", noise_text(r.noise));
  out += fmt::format("planned test: {} ({} windows; the sensor {:.1f}..{:.1f} °C)\n", hours(r.duration_s),
                     r.windows, r.sensor_min_c, r.sensor_max_c);
  out += fmt::format("  start soaked at {} °C, switched on at t = 0\n", r.profile.start_c);
  for (const sim::Segment& s : r.profile.segments)
    out += s.kind == sim::SegmentKind::ramp ? fmt::format("  ramp to {} °C at {:g} °C/min\n", s.temp_c, s.rate_c_per_min)
                                            : fmt::format("  soak at {} °C for {:.0f} min\n", s.temp_c, s.duration_s / 60.0);
  const bool verified = r.verification.has_value();
  out += fmt::format("\n{:<8} {:>12} {:>12} {:>12}", "term", "prior", "target se", "predicted");
  if (verified) out += fmt::format(" {:>12} {:>12} {:>9}", "achieved", "reported", "covered");
  out += "  unit\n";
  for (std::size_t k = 0; k < r.terms.size(); ++k) {
    const TermPlan& t = r.terms[k];
    out += fmt::format("{:<8} {:>12} {:>12} {:>12.4g}", t.term, t.prior == 0.0 ? "-" : fmt::format("{:.4g}", t.prior),
                       std::isfinite(t.target_se) ? fmt::format("{:.4g}", t.target_se) : "-", t.predicted_se);
    if (verified) {
      const Verification& v = *r.verification;
      out += fmt::format(" {:>12.4g} {:>12.4g} {:>8.1f}%", v.achieved_se[k], v.mean_reported_se[k],
                         100.0 * v.coverage_95[k]);
    }
    out += "  " + t.unit + "\n";
  }
  if (verified)
    out += fmt::format("(achieved: the coefficients' spread over {} simulated tests, seeds {}..; reported: the fits' "
                       "own mean standard error; covered: their 95 % intervals holding the truth)\n",
                       r.verification->seeds, r.verification->first_seed);
  out += "\nthe same precision by the standard recipes at the same limits:\n";
  for (const Baseline& b : r.baselines) {
    if (b.met)
      out += fmt::format("  {:<22} {:>9}  ({:+.0f} %)\n", b.recipe, hours(b.duration_s),
                         100.0 * (b.duration_s / r.duration_s - 1.0));
    else
      out += fmt::format("  {:<22} {:>9}  (the closest, {}: {})\n", b.recipe, "never", hours(b.closest.duration_s), baseline_why(b, r));
  }
  for (const TermPlan& t : r.terms)
    if (!std::isnan(t.parameter_log_se))
      out += std::isfinite(t.parameter_log_se)
                 ? fmt::format("{}'s parameter {:g}: predicted within ±{:.0f} % (one standard error of ln θ)\n",
                               t.term, t.parameter, 100.0 * t.parameter_log_se)
                 : fmt::format("{}'s parameter {:g}: not identified by this test\n", t.term, t.parameter);
  for (const PlanNote& n : r.notes) out += "note: " + note_text(n) + "\n";
  out += fmt::format("\nwrote {}, {} (chamber programme), {}, {} and {}\n", r.scenario_file, r.setpoint_file, r.rig_file,
                     r.gyro_file, r.figure_file);
  out += fmt::format("run it: gyrotherm simulate {} --output plan.csv\n", r.scenario_file);
  return out;
}

}  // namespace gyrotherm::studies::plan
