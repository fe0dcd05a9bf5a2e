#include "fit/score.h"

#include <boost/math/distributions/binomial.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>
#include <sstream>
#include <thread>

#include "fit/ols.h"
#include "sim/config_loader.h"
#include "sim/input_error.h"
#include "sim/random.h"
#include "sim/sha256.h"
#include "sim/simulator.h"

namespace gyrotherm::fit {
namespace {

using Json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The true coefficient of each term name the simulator knows ("1" = b0).
std::map<std::string, double> truth_coefficients(const sim::GyroConfig& g) {
  std::map<std::string, double> t = {{"1", g.truth.b0_dph},
                                     {"T", g.truth.b1_dph_per_c},
                                     {"T^2", g.truth.b2_dph_per_c2},
                                     {"dT", g.truth.b3_dph_per_c_per_s}};
  for (const auto& [name, c] : g.hidden.coefficient)
    if (c != 0.0) t[name] = c;
  return t;
}

double& spread_target(sim::GyroConfig& g, std::string_view key) {
  if (key == "b0_dph") return g.truth.b0_dph;
  if (key == "b1_dph_per_c") return g.truth.b1_dph_per_c;
  if (key == "b2_dph_per_c2") return g.truth.b2_dph_per_c2;
  if (key == "b3_dph_per_c_per_s") return g.truth.b3_dph_per_c_per_s;
  if (key == "arw_deg_per_sqrt_h") return g.noise.arw_deg_per_sqrt_h;
  if (key == "bias_instability_dph") return g.noise.bias_instability_dph;
  if (key == "rrw_dph_per_sqrt_h") return g.noise.rrw_dph_per_sqrt_h;
  if (key == "quantization_arcsec") return g.noise.quantization_arcsec;
  if (key == "glitch_rate_per_h") return g.noise.glitch_rate_per_h;
  if (key == "glitch_size_dph") return g.noise.glitch_size_dph;
  assert(false && "spread_target: a key outside sim::kSpreadKeys");
  return g.truth.b0_dph;
}

Summary summarize_values(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  Summary s;
  s.median = quantile(v, 0.5);
  s.p10 = quantile(v, 0.1);
  s.p90 = quantile(v, 0.9);
  s.median_ci = median_interval(v);
  return s;
}

// ---- Byte packing for pack_outcomes / unpack_outcomes -----------------------

class Writer {
 public:
  template <class T>
  void put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out_.append(bytes, sizeof(T));
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    out_ += s;
  }
  void put_doubles(const std::vector<double>& v) {
    put<std::uint64_t>(v.size());
    for (double x : v) put(x);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string get_string() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    need(n);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  std::vector<double> get_doubles() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    need(n * sizeof(double));
    std::vector<double> v(n);
    for (double& x : v) x = get<double>();
    return v;
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw std::runtime_error("score: truncated trial outcomes");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

// ---- JSON helpers ------------------------------------------------------------

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json range_json(Range r) { return Json::array({number(r.low), number(r.high)}); }

std::string fmt_value(double v, const char* spec = "{:.4g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : std::string("not reached");
}

}  // namespace

// ---- Options -------------------------------------------------------------------

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

// ---- Spread --------------------------------------------------------------------

sim::GyroConfig apply_spread(const sim::GyroConfig& gyro, const std::map<std::string, double>& spread,
                             std::uint64_t trial_seed) {
  sim::GyroConfig g = gyro;
  if (spread.empty()) return g;
  for (const auto& [key, r] : spread) {
    if (std::find(sim::kSpreadKeys.begin(), sim::kSpreadKeys.end(), key) == sim::kSpreadKeys.end())
      throw InputError(fmt::format("[spread]: unknown key '{}'", key));
    if (!(r >= 0.0 && r < 1.0))
      throw InputError(fmt::format("[spread]: {} = {}: must be >= 0 and < 1", key, r));
  }
  sim::Rng rng = sim::make_rng(trial_seed, kSpreadStream);
  boost::random::uniform_real_distribution<double> unit(-1.0, 1.0);
  // One draw per key, spread or not, so each key's draw is fixed by the seed alone.
  for (const std::string_view key : sim::kSpreadKeys) {
    const double u = unit(rng);
    const auto it = spread.find(std::string(key));
    if (it == spread.end()) continue;
    spread_target(g, key) *= 1.0 + it->second * u;
  }
  return g;
}

// ---- Statistics ------------------------------------------------------------------

double quantile(std::span<const double> sorted, double p) {
  assert(!sorted.empty() && p >= 0.0 && p <= 1.0);
  const double h = static_cast<double>(sorted.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double w = h - static_cast<double>(lo);
  if (w == 0.0 || lo == hi) return sorted[lo];
  if (!std::isfinite(sorted[hi]) || !std::isfinite(sorted[lo])) return kInf;
  return sorted[lo] + w * (sorted[hi] - sorted[lo]);
}

Range median_interval(std::span<const double> sorted) {
  assert(!sorted.empty());
  const std::size_t n = sorted.size();
  // The largest j with P(B ≤ j − 1) ≤ 0.025, B ~ Bin(n, ½): then
  // P(x_(j) ≤ median ≤ x_(n+1−j)) ≥ 1 − 2·P(B ≤ j − 1) ≥ 0.95.
  const boost::math::binomial_distribution<double> b(static_cast<double>(n), 0.5);
  std::size_t j = 0;
  while (j + 1 <= n / 2 && boost::math::cdf(b, static_cast<double>(j)) <= 0.025) ++j;
  if (j == 0) return {sorted.front(), sorted.back()};  // n < 6: no 95 % interval exists
  return {sorted[j - 1], sorted[n - j]};
}

Range wilson_interval(std::size_t successes, std::size_t n) {
  assert(n > 0 && successes <= n);
  constexpr double z = 1.959963984540054;
  const double nn = static_cast<double>(n);
  const double p = static_cast<double>(successes) / nn;
  const double denominator = 1.0 + z * z / nn;
  const double centre = (p + z * z / (2.0 * nn)) / denominator;
  const double half = z / denominator * std::sqrt(p * (1.0 - p) / nn + z * z / (4.0 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

// ---- Packing ----------------------------------------------------------------------

std::string pack_outcomes(std::span<const TrialOutcome> outcomes) {
  Writer w;
  w.put<std::uint64_t>(outcomes.size());
  for (const TrialOutcome& o : outcomes) {
    w.put<std::uint64_t>(o.index);
    w.put<std::uint64_t>(o.seed);
    w.put_string(o.error);
    w.put(o.before_dph);
    w.put(o.optimum_dph);
    w.put<std::uint64_t>(o.engines.size());
    for (const EngineTrial& e : o.engines) {
      w.put<std::uint8_t>(e.reached ? 1 : 0);
      w.put<std::int64_t>(e.evaluations);
      w.put<std::int64_t>(e.evaluations_to_target);
      w.put(e.seconds);
      w.put(e.gap);
      w.put(e.ratio);
      w.put<std::int32_t>(static_cast<std::int32_t>(e.termination));
      w.put_doubles(e.coefficient_error);
      w.put_doubles(e.curve_gap);
    }
  }
  return w.take();
}

std::vector<TrialOutcome> unpack_outcomes(std::string_view bytes) {
  Reader r(bytes);
  std::vector<TrialOutcome> out(static_cast<std::size_t>(r.get<std::uint64_t>()));
  for (TrialOutcome& o : out) {
    o.index = static_cast<std::size_t>(r.get<std::uint64_t>());
    o.seed = r.get<std::uint64_t>();
    o.error = r.get_string();
    o.before_dph = r.get<double>();
    o.optimum_dph = r.get<double>();
    o.engines.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
    for (EngineTrial& e : o.engines) {
      e.reached = r.get<std::uint8_t>() != 0;
      e.evaluations = static_cast<long>(r.get<std::int64_t>());
      e.evaluations_to_target = static_cast<long>(r.get<std::int64_t>());
      e.seconds = r.get<double>();
      e.gap = r.get<double>();
      e.ratio = r.get<double>();
      e.termination = static_cast<Termination>(r.get<std::int32_t>());
      e.coefficient_error = r.get_doubles();
      e.curve_gap = r.get_doubles();
    }
  }
  if (!r.at_end()) throw std::runtime_error("score: trailing bytes after the trial outcomes");
  return out;
}

// ---- Campaign ---------------------------------------------------------------------

Campaign::Campaign(ScoreOptions options) : options_(std::move(options)) {
  options_.validate();
  scenario_ = sim::load_scenario(options_.scenario);
  rig_ = sim::load_rig(scenario_.rig_file);
  gyro_ = sim::load_gyro(scenario_.gyro_file);
  sim::check_scenario_against_rig(scenario_, rig_, scenario_.rig_file);
  seed_ = options_.seed.value_or(scenario_.seed);
  terms_ = parse_formula(options_.model);

  std::vector<std::string> names = options_.engines;
  if (names.empty())
    for (const EngineInfo& e : engine_registry()) names.push_back(e.name);
  std::set<std::string> seen;
  for (const std::string& name : names) {
    const EngineInfo& info = find_engine(name);
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
    const EngineInfo& info = *infos_[e];
    const auto it = options_.engine_budget.find(info.name);
    const long given = it != options_.engine_budget.end() ? it->second : info.stochastic ? options_.budget : 0;
    budgets_.push_back(given > 0 ? given : info.default_evaluations);
    info.make(settings(e, 0, 0.0));
    largest = std::max(largest, budgets_.back());
  }

  // Coefficient errors: the intercept and every model term with a true value.
  const std::map<std::string, double> truth = truth_coefficients(gyro_);
  error_terms_.push_back("1");
  for (const Term* t : terms_)
    if (truth.count(t->name)) error_terms_.push_back(t->name);

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

EngineSettings Campaign::settings(std::size_t e, std::size_t k, double target_objective) const {
  const EngineInfo& info = *infos_[e];
  EngineSettings s;
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
    Measurement m;
    m.file = fmt::format("{} (trial {}, seed {})", scenario_.name, k, out.seed);
    m.time_s = std::move(record.time_s);
    m.temp_c = std::move(record.temp_c);
    m.gyro_dph = std::move(record.gyro_dph);
    m.temp2_c = std::move(record.temp2_c);
    const PreparedData data = prepare_data(m, options_.pipeline);
    check_columns(terms_, data, options_.pipeline.columns);
    const std::vector<double> parameters = fit_parameters(data.derived, data.series.gyro_dph, terms_);
    std::vector<std::string> names;
    for (const Term* t : terms_) names.push_back(t->name);
    const LinearProblem problem(
        design_matrix(data.derived, terms_, parameters),
        Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                          static_cast<Eigen::Index>(data.series.size())),
        names);
    const std::vector<double> z_optimum = least_squares_optimum(problem);
    const double optimum_gram = problem.objective(z_optimum);  // what engines see
    out.optimum_dph = problem.sigma_two_pass(problem.physical(z_optimum));
    out.before_dph = problem.sigma_y();
    const double target = optimum_gram * (1.0 + options_.target_relative);
    const std::map<std::string, double> truth = truth_coefficients(gyro);

    // 4. Every engine on the same problem.
    for (std::size_t e = 0; e < infos_.size(); ++e) {
      const FitResult f = infos_[e]->make(settings(e, k, target))->fit(problem);
      EngineTrial t;
      t.evaluations = f.evaluations;
      t.seconds = f.seconds;
      t.termination = f.termination;
      for (const HistoryPoint& h : f.history)
        if (h.best_objective <= target) {
          t.reached = true;
          t.evaluations_to_target = h.evaluations;
          break;
        }
      const Coefficients c = problem.physical(f.z);
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
      t.curve_gap.assign(curve_grid_.size(), kInf);
      double best = kInf;
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
  std::atomic<std::size_t> next{0};
  std::mutex progress;
  std::size_t done = 0;
  auto work = [&] {
    for (std::size_t i = next++; i < indices.size(); i = next++) {
      out[i] = run_trial(indices[i]);
      if (observer != nullptr) {
        const std::lock_guard lock(progress);
        observer->on_trial_done(++done, indices.size());
      }
    }
  };
  const auto helpers = static_cast<std::size_t>(std::max(1, threads)) - 1;
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 0; t < std::min(helpers, indices.size()); ++t) pool.emplace_back(work);
    work();
  }
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
  b.file_sha256 = {{"scenario", sim::sha256_file_hex(options_.scenario)},
                   {"rig", sim::sha256_file_hex(scenario_.rig_file)},
                   {"gyro", sim::sha256_file_hex(scenario_.gyro_file)}};
  b.model = formula_text(terms_);
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
    b.before_median_dph = summarize_values(before).median;
    b.optimum_median_dph = summarize_values(optimum).median;
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
      to_target.push_back(t.reached ? static_cast<double>(t.evaluations_to_target) : kInf);
      seconds_to_target.push_back(t.reached ? t.seconds : kInf);
      seconds.push_back(t.seconds);
      evaluations.push_back(static_cast<double>(t.evaluations));
      gap.push_back(t.gap);
      ratio.push_back(t.ratio);
      for (std::size_t j = 0; j < errors.size(); ++j) errors[j].push_back(t.coefficient_error[j]);
      ++s.terminations[to_string(t.termination)];
      most_evaluations = std::max(most_evaluations, t.evaluations);
    }
    s.success_rate = static_cast<double>(s.reached) / static_cast<double>(n);
    s.success_ci = wilson_interval(s.reached, n);
    s.evaluations_to_target = summarize_values(to_target);
    s.seconds_to_target = summarize_values(seconds_to_target);
    s.seconds = summarize_values(seconds);
    s.evaluations = summarize_values(evaluations);
    s.gap = summarize_values(gap);
    s.ratio = summarize_values(ratio);
    for (auto& v : errors) s.coefficient_error.push_back(summarize_values(std::move(v)));
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

// ---- Output -----------------------------------------------------------------------

namespace {

void put_summary(Json& j, const std::string& name, const Summary& s, bool with_p10 = false) {
  j[name + "_median"] = number(s.median);
  if (with_p10) j[name + "_p10"] = number(s.p10);
  j[name + "_p90"] = number(s.p90);
}

}  // namespace

std::string scoreboard_json(const Scoreboard& b) {
  Json j;
  j["scenario"] = b.scenario;
  j["trials"] = b.trials;
  j["seed"] = b.seed;
  Json engines = Json::object();
  for (const EngineScore& e : b.engines) {
    Json x;
    // The fields of DESIGN.md first.
    x["success_rate"] = e.success_rate;
    x["evals_to_target_median"] = number(e.evaluations_to_target.median);
    x["seconds_median"] = number(e.seconds_to_target.median);
    x["gap_median"] = e.gap.median;
    Json errors = Json::object(), errors90 = Json::object(), errors_ci = Json::object();
    for (std::size_t k = 0; k < b.error_terms.size(); ++k) {
      errors[b.error_terms[k]] = e.coefficient_error[k].median;
      errors90[b.error_terms[k]] = e.coefficient_error[k].p90;
      errors_ci[b.error_terms[k]] = range_json(e.coefficient_error[k].median_ci);
    }
    x["coefficient_error_median"] = errors;
    x["ratio_median"] = e.ratio.median;
    // More.
    x["stochastic"] = e.stochastic;
    x["budget"] = e.budget;
    x["reached"] = e.reached;
    x["evals_to_target_p90"] = number(e.evaluations_to_target.p90);
    x["seconds_p90"] = number(e.seconds_to_target.p90);
    put_summary(x, "seconds_run", e.seconds);
    put_summary(x, "evaluations", e.evaluations);
    x["gap_p90"] = e.gap.p90;
    x["coefficient_error_p90"] = errors90;
    x["ratio_p10"] = e.ratio.p10;
    Json terminations = Json::object();
    for (const auto& [name, count] : e.terminations) terminations[name] = count;
    x["terminations"] = terminations;
    x["ci95"] = {{"success_rate", range_json(e.success_ci)},
                 {"evals_to_target_median", range_json(e.evaluations_to_target.median_ci)},
                 {"gap_median", range_json(e.gap.median_ci)},
                 {"ratio_median", range_json(e.ratio.median_ci)},
                 {"coefficient_error_median", errors_ci}};
    engines[e.engine] = x;
  }
  j["engines"] = engines;
  j["model"] = b.model;
  j["target"] = fmt::format("sigma <= optimum * (1 + {:g})", b.target_relative);
  j["target_relative"] = b.target_relative;
  j["seeds"] = {{"first", b.seed}, {"last", b.seed + (b.trials - 1)}};
  Json spread = Json::object();
  for (const auto& [key, r] : b.spread) spread[key] = r;
  j["spread"] = spread;
  j["error_terms"] = b.error_terms;
  j["instability_before_median_dph"] = b.before_median_dph;
  j["optimum_median_dph"] = b.optimum_median_dph;
  j["scenario_file"] = b.scenario_file;
  Json files = Json::object();
  for (const auto& [k, v] : b.file_sha256) files[k] = v;
  j["file_sha256"] = files;
  j["run"] = {{"threads", b.threads}, {"processes", b.processes}, {"seconds", b.seconds}};
  return j.dump(2) + "\n";
}

std::string scoreboard_markdown(const Scoreboard& b) {
  std::string md = fmt::format("# Scoreboard: {}, {} trials\n\n", b.scenario, b.trials);
  std::string spread;
  for (const auto& [key, r] : b.spread) spread += fmt::format("{}{} ±{:g} %", spread.empty() ? "" : ", ", key, 100.0 * r);
  md += fmt::format(
      "Scenario `{}`, seeds {}..{}, model `B = b0 + {}`; spread: {}. Target: σ ≤ σ*·(1 + {:g}), σ* the "
      "least-squares optimum of each trial (median σ* {:.6g} °/h, median raw instability {:.6g} °/h). "
      "Medians over the trials, evaluations with their 95 % interval; \"not reached\": the median "
      "trial did not reach the target. Coefficient errors are |fit − truth| / |truth|, median / 90th percentile. "
      "{} s on {} thread(s) × {} process(es).\n\n",
      b.scenario_file, b.seed, b.seed + (b.trials - 1), b.model, spread.empty() ? "none" : spread,
      b.target_relative, b.optimum_median_dph, b.before_median_dph, fmt::format("{:.2f}", b.seconds),
      b.threads, b.processes);
  md += "| engine | success | evaluations to target | seconds to target | final gap (median / p90) | ratio |";
  for (const std::string& t : b.error_terms) md += fmt::format(" error {} |", t == "1" ? "b0" : t);
  md += "\n|---|---|---|---|---|---|";
  for (std::size_t k = 0; k < b.error_terms.size(); ++k) md += "---|";
  md += "\n";
  for (const EngineScore& e : b.engines) {
    const Summary& ett = e.evaluations_to_target;
    const std::string evaluations =
        std::isfinite(ett.median) ? fmt::format("{:.0f} [{}, {}]", ett.median, fmt_value(ett.median_ci.low, "{:.0f}"),
                                                fmt_value(ett.median_ci.high, "{:.0f}"))
                                  : std::string("not reached");
    md += fmt::format("| {} | {:.0f} % ({}/{}) | {} | {} | {:.2g} / {:.2g} | {:.3f} |", e.engine,
                      100.0 * e.success_rate, e.reached, b.trials, evaluations,
                      fmt_value(e.seconds_to_target.median, "{:.2g}"), e.gap.median, e.gap.p90, e.ratio.median);
    for (const Summary& s : e.coefficient_error)
      md += fmt::format(" {:.2g} % / {:.2g} % |", 100.0 * s.median, 100.0 * s.p90);
    md += "\n";
  }
  md += "\nConvergence (median and quartiles of the gap of the best σ so far against evaluations): "
        "`convergence.csv`, `convergence.png`.\n";
  return md;
}

std::string convergence_csv(const Scoreboard& b) {
  std::string csv = "engine,evaluations,gap_q25,gap_median,gap_q75\n";
  auto cell = [](double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string(); };
  for (const EngineScore& e : b.engines)
    for (const CurvePoint& p : e.curve)
      csv += fmt::format("{},{},{},{},{}\n", e.engine, p.evaluations, cell(p.q25), cell(p.median), cell(p.q75));
  return csv;
}

// ---- Baseline ----------------------------------------------------------------------

namespace {

struct MetricRule {
  bool higher_is_worse;
  bool clip_at_target;  // values ≤ ε are all "at the optimum"
};

MetricRule rule_of(const std::string& metric) {
  if (metric == "success_rate" || metric == "ratio_median") return {false, false};
  if (metric == "gap_median") return {true, true};
  return {true, false};  // evals_to_target_median, coefficient_error_median.<term>
}

[[noreturn]] void bad(const std::string& where, const std::string& field, const std::string& expected) {
  throw InputError(fmt::format("{}: {}: expected {} (a saved 'gyrotherm score --json')", where, field, expected));
}

double read_bound(const Json& v, const std::string& where, const std::string& field) {
  if (v.is_null()) return kInf;  // "not reached"
  if (!v.is_number()) bad(where, field, "a number or null");
  return v.get<double>();
}

BaselineMetric read_metric(const Json& value, const Json& ci, const std::string& where,
                           const std::string& field, const std::string& ci_field) {
  BaselineMetric m;
  m.value = read_bound(value, where, field);
  if (!ci.is_array() || ci.size() != 2) bad(where, ci_field, "[low, high]");
  m.ci = {read_bound(ci[0], where, ci_field + "[0]"), read_bound(ci[1], where, ci_field + "[1]")};
  return m;
}

const Json& member(const Json& j, const std::string& key, const std::string& where, const std::string& path,
                   const std::string& expected) {
  if (!j.is_object() || !j.contains(key)) bad(where, path, expected);
  return j.at(key);
}

}  // namespace

Baseline parse_baseline(std::string_view text, const std::string& where) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", where, e.what()));
  }
  Baseline b;
  b.file = where;
  const Json& model = member(j, "model", where, "model", "a string");
  if (!model.is_string()) bad(where, "model", "a string");
  b.model = model.get<std::string>();
  const Json& target = member(j, "target_relative", where, "target_relative", "a number");
  if (!target.is_number()) bad(where, "target_relative", "a number");
  b.target_relative = target.get<double>();
  const Json& trials = member(j, "trials", where, "trials", "a whole number");
  if (!trials.is_number_unsigned()) bad(where, "trials", "a whole number");
  b.trials = trials.get<std::size_t>();
  if (j.contains("scenario") && j["scenario"].is_string()) b.scenario = j["scenario"].get<std::string>();
  if (j.contains("file_sha256") && j["file_sha256"].is_object())
    for (const auto& [k, v] : j["file_sha256"].items())
      if (v.is_string()) b.file_sha256[k] = v.get<std::string>();
  const Json& engines = member(j, "engines", where, "engines", "an object (engine -> scores)");
  if (!engines.is_object()) bad(where, "engines", "an object (engine -> scores)");
  for (const auto& [name, e] : engines.items()) {
    const std::string at = "engines." + name;
    const Json& ci = member(e, "ci95", where, at + ".ci95", "an object of 95 % intervals");
    auto& metrics = b.engines[name];
    for (const char* metric : {"success_rate", "evals_to_target_median", "gap_median", "ratio_median"})
      metrics[metric] = read_metric(member(e, metric, where, at + "." + metric, "a number or null"),
                                    member(ci, metric, where, at + ".ci95." + metric, "[low, high]"), where,
                                    at + "." + metric, at + ".ci95." + metric);
    const Json& errors = member(e, "coefficient_error_median", where, at + ".coefficient_error_median",
                                "an object (term -> value)");
    const Json& errors_ci = member(ci, "coefficient_error_median", where, at + ".ci95.coefficient_error_median",
                                   "an object (term -> [low, high])");
    if (!errors.is_object()) bad(where, at + ".coefficient_error_median", "an object (term -> value)");
    for (const auto& [term, v] : errors.items())
      metrics["coefficient_error_median." + term] =
          read_metric(v, member(errors_ci, term, where, at + ".ci95.coefficient_error_median." + term, "[low, high]"),
                      where, at + ".coefficient_error_median." + term,
                      at + ".ci95.coefficient_error_median." + term);
  }
  return b;
}

Baseline load_baseline(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(fmt::format("{}: no such file (a saved 'gyrotherm score --json')", file.string()));
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return parse_baseline(s.str(), file.string());
}

std::map<std::string, BaselineMetric> checked_metrics(const Scoreboard& board, const EngineScore& e) {
  std::map<std::string, BaselineMetric> m;
  m["success_rate"] = {e.success_rate, e.success_ci};
  m["evals_to_target_median"] = {e.evaluations_to_target.median, e.evaluations_to_target.median_ci};
  m["gap_median"] = {e.gap.median, e.gap.median_ci};
  m["ratio_median"] = {e.ratio.median, e.ratio.median_ci};
  for (std::size_t k = 0; k < board.error_terms.size(); ++k)
    m["coefficient_error_median." + board.error_terms[k]] = {e.coefficient_error[k].median,
                                                            e.coefficient_error[k].median_ci};
  return m;
}

BaselineComparison compare_to_baseline(const Scoreboard& current, const Baseline& baseline) {
  if (baseline.model != current.model)
    throw InputError(fmt::format("{}: made for the model '{}', this campaign fits '{}'", baseline.file,
                                 baseline.model, current.model));
  if (baseline.target_relative != current.target_relative)
    throw InputError(fmt::format("{}: made with the target optimum·(1 + {:g}), this campaign uses {:g}",
                                 baseline.file, baseline.target_relative, current.target_relative));
  BaselineComparison out;
  for (const auto& [file, sha] : current.file_sha256) {
    const auto it = baseline.file_sha256.find(file);
    if (it != baseline.file_sha256.end() && it->second != sha)
      out.notes.push_back(fmt::format("the baseline was made with another {} file (SHA-256 differs); "
                                      "if it changed on purpose, make the baseline again",
                                      file));
  }
  const double eps = current.target_relative;
  for (const EngineScore& e : current.engines) {
    const auto base = baseline.engines.find(e.engine);
    if (base == baseline.engines.end()) {
      out.notes.push_back(fmt::format("no baseline for engine '{}'", e.engine));
      continue;
    }
    for (const auto& [metric, now] : checked_metrics(current, e)) {
      const auto b = base->second.find(metric);
      if (b == base->second.end()) {
        out.notes.push_back(fmt::format("{}: no baseline for {}", e.engine, metric));
        continue;
      }
      const MetricRule rule = rule_of(metric);
      Range c = now.ci, r = b->second.ci;
      if (rule.clip_at_target) {
        c = {std::max(c.low, eps), std::max(c.high, eps)};
        r = {std::max(r.low, eps), std::max(r.high, eps)};
      }
      // A relative slack of 1e-9 keeps last-bit differences between machines out.
      const bool worse = rule.higher_is_worse
                             ? std::isfinite(r.high) && c.low > r.high + 1e-9 * std::abs(r.high)
                             : std::isfinite(r.low) && c.high < r.low - 1e-9 * std::abs(r.low);
      if (!worse) continue;
      out.regressions.push_back(
          {e.engine, metric,
           fmt::format("{}: {} = {} (95 % interval {}..{}) is {} the baseline's {} ({}..{}), beyond Monte Carlo noise",
                       e.engine, metric, fmt_value(now.value, "{:.4g}"), fmt_value(now.ci.low, "{:.4g}"),
                       fmt_value(now.ci.high, "{:.4g}"), rule.higher_is_worse ? "above" : "below",
                       fmt_value(b->second.value, "{:.4g}"), fmt_value(b->second.ci.low, "{:.4g}"),
                       fmt_value(b->second.ci.high, "{:.4g}"))});
    }
  }
  return out;
}

}  // namespace gyrotherm::fit
