#include "studies/score/campaign.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <set>

#include "studies/simulated.h"
#include "fit/engines/ols.h"
#include "sim/config_loader.h"
#include "sim/util/input_error.h"
#include "sim/util/parallel_for.h"
#include "sim/util/sha256.h"
#include "studies/score/spread.h"
#include "sim/util/numbers.h"

namespace gyrotherm::studies {

namespace {


}  // namespace

namespace {

long parse_count(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  long v = -1;
  try {
    v = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || v < 0) throw InputError(fmt::format("{}: '{}' is not a whole number >= 0", what, text));
  return v;
}

}  // namespace

void ScoreOptions::add_budget(const std::string& text) {
  if (text.find('=') == std::string::npos) {
    budget = parse_count(text, "--budget " + text);
    return;
  }
  if (text.front() == '=') throw InputError(fmt::format("--budget {}: expected N or ENGINE=N", text));
  const fit::KeyValue kv = fit::parse_key_value(text, "--budget", false);
  engine_budget[kv.key] = parse_count(kv.value, "--budget " + text);
}

void ScoreOptions::add_engine_option(const std::string& text) {
  const fit::KeyValue kv = fit::parse_key_value(text, "--option", true);
  engine_options[kv.scope][kv.key] = kv.value;
}

void ScoreOptions::validate() const {
  if (trials < 1 || trials > 10'000'000)
    throw InputError(fmt::format("--trials {}: must be a whole number from 1 to 10000000", trials));
  if (budget < 0) throw InputError(fmt::format("--budget {}: must be >= 0 (0: the engine's default)", budget));
  for (const auto& [engine, b] : engine_budget)
    if (b < 0)
      throw InputError(fmt::format("--budget {}={}: must be >= 0 (0: the engine's default)", engine, b));
  if (!(target_relative > 0.0 && target_relative < 1.0))
    throw InputError(fmt::format("target_relative = {}: must be > 0 and < 1", target_relative));
  if (curve_points_per_decade < 1 || curve_points_per_decade > 100)
    throw InputError(fmt::format("curve_points_per_decade = {}: must be from 1 to 100",
                                 curve_points_per_decade));
}

Campaign::Campaign(ScoreOptions options) : options_(std::move(options)) {
  options_.validate();
  scenario_ = sim::load_scenario(options_.scenario);
  rig_ = sim::load_rig(scenario_.rig_file);
  gyro_ = sim::load_gyro(scenario_.gyro_file);
  sim::check_scenario_against_rig(scenario_, rig_, scenario_.rig_file);
  seed_ = options_.seed.value_or(scenario_.seed);
  terms_ = fit::parse_formula(options_.model);

  std::vector<std::string> names = options_.engines;
  if (names.empty())
    for (const fit::EngineInfo& e : fit::engine_registry())
      if (e.minimises_sigma) names.push_back(e.name);
  std::set<std::string> seen;
  for (const std::string& name : names) {
    const fit::EngineInfo& info = fit::find_engine(name);
    if (!seen.insert(name).second)
      throw InputError(fmt::format("--engines: '{}' is named twice", name));
    infos_.push_back(&info);
    engine_names_.push_back(name);
  }
  for (const auto& [name, b] : options_.engine_budget)
    if (!seen.count(name))
      throw InputError(fmt::format("--budget {}={}: '{}' is not among the campaign's engines", name, b, name));
  for (const auto& [name, kv] : options_.engine_options)
    if (!seen.count(name))
      throw InputError(fmt::format("--option {}:...: '{}' is not among the campaign's engines", name, name));

  // Budgets, and each engine's settings checked once before any trial.
  long largest = 10;
  for (std::size_t e = 0; e < infos_.size(); ++e) {
    const fit::EngineInfo& info = *infos_[e];
    const auto it = options_.engine_budget.find(info.name);
    const long given = it != options_.engine_budget.end() ? it->second : info.stochastic ? options_.budget : 0;
    budgets_.push_back(given > 0 ? given : info.default_evaluations);
    info.make(settings(e, 0, 0.0));
    largest = std::max(largest, budgets_.back());
  }

  // Coefficient errors: the intercept and every model term with a true value.
  const std::map<std::string, double> truth = sim::true_coefficients(gyro_);
  error_terms_.push_back("1");
  for (const fit::Term* t : terms_)
    if (truth.count(std::string(t->name))) error_terms_.emplace_back(t->name);

  // The convergence grid: log-spaced evaluation counts 1 … the largest budget.
  for (int i = 0;; ++i) {
    const auto g = std::lround(std::pow(10.0, static_cast<double>(i) / options_.curve_points_per_decade));
    if (g >= largest) {
      curve_grid_.push_back(largest);
      break;
    }
    if (curve_grid_.empty() || g > curve_grid_.back()) curve_grid_.push_back(g);
  }

  // The temperatures every trial shares, integrated once, last: only after
  // every input has been checked.
  trace_ = sim::Simulator(scenario_, rig_, gyro_).run_thermal();
}

fit::EngineSettings Campaign::settings(std::size_t e, std::size_t k, double target_objective) const {
  const fit::EngineInfo& info = *infos_[e];
  fit::EngineSettings s;
  s.seed = trial_seed(k);
  const auto it = options_.engine_budget.find(info.name);
  s.max_evaluations = it != options_.engine_budget.end() ? it->second : info.stochastic ? options_.budget : 0;
  s.target_objective = target_objective;
  const auto o = options_.engine_options.find(info.name);
  if (o != options_.engine_options.end()) s.options = o->second;
  return s;
}

TrialOutcome Campaign::run_trial(std::size_t k) const {
  TrialOutcome out;
  out.index = k;
  out.seed = trial_seed(k);
  try {
    // 1–2. The trial's gyro and noise.
    sim::Scenario scenario = scenario_;
    scenario.seed = out.seed;
    const sim::GyroConfig gyro = apply_spread(gyro_, scenario_.spread, out.seed);
    // 3. Simulate once (on the campaign's thermal trace), prepare once, the
    // optimum once.
    sim::SimulationResult record =
        sim::Simulator(std::move(scenario), rig_, gyro).record(trace_);
    const fit::Measurement m = measurement_of(std::move(record), fmt::format("{} (trial {}, seed {})", scenario_.name, k, out.seed));
    const fit::PreparedData data = fit::prepare_data(m, options_.pipeline);
    fit::check_columns(terms_, data, options_.pipeline.columns);
    const std::vector<double> parameters = fit::fit_parameters(data.derived, data.series.gyro_dph, terms_);
    const fit::LinearProblem problem(
        fit::design_matrix(data.derived, terms_, parameters),
        Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                          static_cast<Eigen::Index>(data.series.size())),
        fit::term_names(terms_));
    const std::vector<double> z_optimum = fit::least_squares_optimum(problem);
    const double optimum_gram = problem.objective(z_optimum);  // what engines see
    out.optimum_dph = problem.sigma_two_pass(problem.physical(z_optimum));
    out.before_dph = problem.sigma_y();
    const double target = optimum_gram * (1.0 + options_.target_relative);
    const std::map<std::string, double> truth = sim::true_coefficients(gyro);

    // 4. Every engine on the same problem.
    for (std::size_t e = 0; e < infos_.size(); ++e) {
      const fit::FitResult f = infos_[e]->make(settings(e, k, target))->fit(problem);
      EngineTrial t;
      t.evaluations = f.evaluations;
      t.seconds = f.seconds;
      t.termination = f.termination;
      for (const fit::HistoryPoint& h : f.history)
        if (h.best_objective <= target) {
          t.reached = true;
          t.evaluations_to_target = h.evaluations;
          break;
        }
      const fit::Coefficients c = problem.physical(f.z);
      const double after = problem.sigma_two_pass(c);
      t.gap = after / out.optimum_dph - 1.0;
      t.ratio = out.before_dph / after;
      for (const std::string& term : error_terms_) {
        double value = c.intercept;
        for (std::size_t j = 0; j < terms_.size(); ++j)
          if (terms_[j]->name == term) value = c.b[j];
        const double true_value = truth.at(term);
        t.coefficient_error.push_back(std::abs(value - true_value) / std::abs(true_value));
      }
      // The best σ so far at each grid point, as a gap in the engines' (Gram) form.
      t.curve_gap.assign(curve_grid_.size(), kInfinity);
      double best = kInfinity;
      std::size_t h = 0;
      for (std::size_t i = 0; i < curve_grid_.size(); ++i) {
        for (; h < f.history.size() && f.history[h].evaluations <= curve_grid_[i]; ++h)
          best = f.history[h].best_objective;
        if (std::isfinite(best)) t.curve_gap[i] = std::max(0.0, best / optimum_gram - 1.0);
      }
      out.engines.push_back(std::move(t));
    }
  } catch (const std::exception& e) {
    out.error = e.what();
    out.engines.clear();
  }
  return out;
}

std::vector<TrialOutcome> Campaign::run(std::span<const std::size_t> indices, int threads,
                                        ScoreObserver* observer) const {
  std::vector<TrialOutcome> out(indices.size());
  parallel_for(
      indices.size(), threads, [&](std::size_t i) { out[i] = run_trial(indices[i]); },
      [&](std::size_t done) {
        if (observer != nullptr) observer->on_trial_done(done, indices.size());
      });
  return out;
}

Scoreboard Campaign::summarize(std::vector<TrialOutcome> outcomes) const {
  std::sort(outcomes.begin(), outcomes.end(),
            [](const TrialOutcome& a, const TrialOutcome& b) { return a.index < b.index; });
  const std::size_t n = trials();
  if (outcomes.size() != n)
    throw InputError(fmt::format("score: {} trial outcomes for a campaign of {}", outcomes.size(), n));
  for (std::size_t k = 0; k < n; ++k) {
    const TrialOutcome& o = outcomes[k];
    if (o.index != k) throw InputError(fmt::format("score: trial {} is missing", k));
    if (!o.ok())
      throw InputError(fmt::format("score: trial {} (seed {}) failed: {}", k, o.seed, o.error));
    assert(o.engines.size() == infos_.size());
  }

  Scoreboard b;
  b.scenario = scenario_.name;
  b.scenario_file = options_.scenario.string();
  b.file_sha256 = {{"scenario", sha256_file_hex(options_.scenario)},
                   {"rig", sha256_file_hex(scenario_.rig_file)},
                   {"gyro", sha256_file_hex(scenario_.gyro_file)}};
  b.model = fit::formula_text(terms_);
  b.trials = n;
  b.seed = seed_;
  b.target_relative = options_.target_relative;
  b.spread = scenario_.spread;
  b.error_terms = error_terms_;
  {
    std::vector<double> before, optimum;
    for (const TrialOutcome& o : outcomes) {
      before.push_back(o.before_dph);
      optimum.push_back(o.optimum_dph);
    }
    b.before_median_dph = summary_of(before).median;
    b.optimum_median_dph = summary_of(optimum).median;
  }

  for (std::size_t e = 0; e < infos_.size(); ++e) {
    EngineScore s;
    s.engine = engine_names_[e];
    s.stochastic = infos_[e]->stochastic;
    s.budget = budgets_[e];
    std::vector<double> to_target, seconds_to_target, seconds, evaluations, gap, ratio;
    std::vector<std::vector<double>> errors(error_terms_.size());
    long most_evaluations = 0;
    for (const TrialOutcome& o : outcomes) {
      const EngineTrial& t = o.engines[e];
      s.reached += t.reached ? 1 : 0;
      to_target.push_back(t.reached ? static_cast<double>(t.evaluations_to_target) : kInfinity);
      seconds_to_target.push_back(t.reached ? t.seconds : kInfinity);
      seconds.push_back(t.seconds);
      evaluations.push_back(static_cast<double>(t.evaluations));
      gap.push_back(t.gap);
      ratio.push_back(t.ratio);
      for (std::size_t j = 0; j < errors.size(); ++j) errors[j].push_back(t.coefficient_error[j]);
      ++s.terminations[fit::to_string(t.termination)];
      most_evaluations = std::max(most_evaluations, t.evaluations);
    }
    s.success_rate = static_cast<double>(s.reached) / static_cast<double>(n);
    s.success_ci = wilson_interval(s.reached, n);
    s.evaluations_to_target = summary_of(to_target);
    s.seconds_to_target = summary_of(seconds_to_target);
    s.seconds = summary_of(seconds);
    s.evaluations = summary_of(evaluations);
    s.gap = summary_of(gap);
    s.ratio = summary_of(ratio);
    for (auto& v : errors) s.coefficient_error.push_back(summary_of(std::move(v)));
    for (std::size_t i = 0; i < curve_grid_.size(); ++i) {
      if (i > 0 && curve_grid_[i - 1] >= most_evaluations) break;  // up to the first point past the last evaluation
      std::vector<double> v;
      for (const TrialOutcome& o : outcomes) v.push_back(o.engines[e].curve_gap[i]);
      std::sort(v.begin(), v.end());
      s.curve.push_back({curve_grid_[i], quantile(v, 0.25), quantile(v, 0.5), quantile(v, 0.75)});
    }
    b.engines.push_back(std::move(s));
  }
  return b;
}

}  // namespace gyrotherm::studies
