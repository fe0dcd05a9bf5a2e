#pragma once
// One interface for every fitting engine (docs/architecture.md, "House rules").
//
// An engine minimises LinearProblem::objective (σ of the residual, the paper's
// eq. 6) over the unit box z ∈ [−1, 1]^m. It takes a seed, a budget of
// objective evaluations and a target σ; it returns a FitResult summary. An
// engine that does not converge says so in the result; it never prints and
// never exits. Progress goes to an optional FitObserver.
//
// Engines count evaluations through an Evaluator, which also keeps the best
// point, the history of the best σ against evaluations, and decides when the
// budget is spent or the target reached, so every engine is measured the same
// way.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fit/engines/engine_options.h"
#include "fit/model/linear_problem.h"

namespace gyrotherm::fit {

enum class Termination {
  exact,             // a closed-form answer (ols, stepwise)
  target_reached,    // σ ≤ the target
  budget_exhausted,  // the evaluation budget is spent
  max_iterations,    // the engine's own iteration limit (e.g. IAFSA's G_max)
  converged,         // the engine's own convergence test
  stopped,           // the observer asked to stop
};
const char* to_string(Termination t);

struct HistoryPoint {
  long evaluations = 0;
  double best_objective = 0.0;
};

// A 95 % confidence interval in physical units.
struct Interval {
  double lower = 0.0;
  double upper = 0.0;
};

// How an engine's intervals were computed: data, rendered by
// interval_method_text() (the fit's JSON `interval_method`, its text report).
enum class IntervalKind {
  none,              // the engine gives no intervals
  noise_bootstrap,   // ols: parametric bootstrap from the identified noise
  noise_covariance,  // ols: the least-squares covariance under the identified noise
  gls,               // gls: generalised least squares under the identified noise
  newey_west,        // ols: pre-whitened Newey–West long-run variance
  cosine,            // ols: equal-weighted cosine long-run variance
};
const char* to_string(IntervalKind k);

struct IntervalMethod {
  IntervalKind kind = IntervalKind::none;
  bool no_noise_model = false;  // a long-run variance because no noise model could be identified
  int draws = 0;                // noise_bootstrap: per noise structure
  long lags = 0;                // newey_west: the Bartlett kernel's lags; cosine: its frequencies
  double dof = 0;               // Student t's (the smallest Satterthwaite dof where they differ)
  std::size_t widest_of = 0;    // gls: the variance is the widest under this many models (0: the identified one)
  bool has_lag1 = false;        // ols: the residual's lag-1 autocorrelation, below
  double lag1_autocorrelation = 0;
  bool linearised_parameters = false;  // the fitted parameters' uncertainty is in (fit/pipeline.h)
};

// Per term, from the regression engines: ols and gls give 95 % intervals of
// the physical b_j and p-values, stepwise p-values and the terms it kept.
struct TermInference {
  std::vector<Interval> intervals;  // empty: none
  IntervalMethod interval_method;   // how the intervals were computed
  std::vector<double> p_values;     // empty: none
  std::vector<bool> kept;           // stepwise: which terms are in the model; empty: every one
};

// How an engine's run went, as data: the method, and what the engine adds
// (stepwise's steps, a school's or population's size and seed, why a pagmo
// run ended before its budget). run_text() words it: the reports' engine
// line and the fit file's "message".
struct RunDetail {
  enum class Kind {
    qr,                 // ols: least squares by column-pivoting QR
    gls,                // gls by the noise's semi-separable Cholesky factor
    gls_without_noise,  // gls where no noise model was identified: ordinary least squares
    stepwise,           // steps and the terms kept
    fish_swarm,         // afsa, iafsa: fish, iterations of the limit, Visual and Step
    pagmo,              // pso, de, cmaes, abc: population, seed, end
  };
  Kind kind = Kind::qr;
  struct Step {
    std::string term;
    bool entered = true;  // else left
  };
  std::vector<Step> steps;        // stepwise, in order
  std::vector<std::string> kept;  // stepwise: the terms kept
  long fish = 0, iteration_limit = 0;
  double visual = 0.0, step = 0.0;  // fish_swarm: box widths
  long population = 0;              // pagmo
  std::uint64_t seed = 0;           // pagmo
  enum class End { budget_or_target, generation_limit, collapsed, non_finite, observer };
  End end = End::budget_or_target;  // pagmo
  unsigned generation_limit = 0;    // pagmo, End::generation_limit
};

struct FitResult {
  std::string engine;
  std::vector<double> z;              // best point in the unit box
  double objective = 0.0;             // σ at z (Gram form)
  long evaluations = 0;
  long iterations = 0;
  double seconds = 0.0;
  Termination termination = Termination::budget_exhausted;
  RunDetail detail;
  std::vector<HistoryPoint> history;  // best σ each time it improved
  // What a statistical engine says of each term besides its value; empty for
  // the search engines (afsa, iafsa, pagmo's), which give a point alone.
  TermInference inference;
  std::string brief_report() const;
};
// The engine's own line for its run (brief_report's parenthesis).
std::string run_text(const FitResult& r);

struct NoiseModel;
// "least-squares covariance under the identified noise (…); Student t …":
// the method in words, with `noise` (the one the intervals were computed
// under) described where the method rests on it; "" for none.
std::string interval_method_text(const IntervalMethod& method, const NoiseModel* noise);

// Common settings; `options` holds engine-specific KEY=VALUE pairs.
struct EngineSettings {
  std::uint64_t seed = 1;
  long max_evaluations = 0;     // 0: the engine's default budget
  double target_objective = 0;  // stop once σ ≤ this (0: no target)
  std::map<std::string, std::string> options;
};

// An engine option as the command line gives it: KEY=VALUE, or with a scope
// ENGINE:KEY=VALUE (score, several engines). The one parser of both; throws
// InputError naming `option` ("--option") and the expected form.
struct KeyValue {
  std::string scope;  // ENGINE, or "" unscoped
  std::string key, value;
};
KeyValue parse_key_value(const std::string& text, const std::string& option, bool scoped);

// The settings of one fit from the command line: --seed, --budget (≥ 0),
// --target (finite, ≥ 0) and the --option KEY=VALUE list.
EngineSettings engine_settings(std::uint64_t seed, long budget, double target,
                               const std::vector<std::string>& key_values);

class FitObserver {
 public:
  virtual ~FitObserver() = default;
  // Called once per engine iteration; return false to stop the engine.
  virtual bool on_iteration(long iteration, long evaluations, double best_objective) = 0;
};

// Counts evaluations, keeps the best point and the history, and knows when to stop.
class Evaluator {
 public:
  Evaluator(const LinearProblem& problem, long max_evaluations, double target_objective);

  // σ at z (clamped into the box); updates the best point.
  double operator()(std::span<const double> z);
  bool budget_left() const { return evaluations_ < max_evaluations_; }
  bool target_reached() const { return target_ > 0.0 && best_ <= target_; }
  bool done() const { return !budget_left() || target_reached(); }

  long evaluations() const { return evaluations_; }
  long max_evaluations() const { return max_evaluations_; }
  double best() const { return best_; }
  const std::vector<double>& best_point() const { return best_z_; }
  const std::vector<HistoryPoint>& history() const { return history_; }
  std::size_t dimension() const { return problem_.dimension(); }
  const LinearProblem& problem() const { return problem_; }

  // Fills the common fields of a result (z, objective, evaluations, history,
  // seconds since construction) and chooses the termination when the
  // evaluator decided it (target or budget); otherwise uses `fallback`.
  FitResult result(std::string engine, long iterations, Termination fallback, RunDetail detail) const;

 private:
  const LinearProblem& problem_;
  long max_evaluations_;
  double target_;
  long evaluations_ = 0;
  double best_ = std::numeric_limits<double>::infinity();
  std::vector<double> best_z_;
  std::vector<double> clamped_;
  std::vector<HistoryPoint> history_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

class Engine {
 public:
  virtual ~Engine() = default;
  virtual FitResult fit(const LinearProblem& problem, FitObserver* observer = nullptr) const = 0;
};

// One registry entry per engine. `make` validates the settings and throws
// InputError naming the option, its value and the rule.
struct EngineInfo {
  std::string name;
  std::string description;
  bool stochastic = false;
  long default_evaluations = 0;
  // It minimises the paper's σ (eq. 6), as score and reproduce compare
  // engines on; gls estimates otherwise and is left out of their defaults.
  bool minimises_sigma = true;
  std::vector<OptionInfo> options;  // from the engine's option table (fit/engines/engine_options.h)
  std::function<std::unique_ptr<Engine>(const EngineSettings&)> make;
};

const std::vector<EngineInfo>& engine_registry();
// Throws InputError listing the known engines.
const EngineInfo& find_engine(std::string_view name);

// The stopping rules every engine's Options share: throws InputError unless
// max_evaluations ≥ 1 and target_objective is finite and ≥ 0.
void check_stopping_rules(std::string_view engine, long max_evaluations, double target_objective);

// The common part of an engine's `make`: its Options from the table and the
// KEY=VALUE strings, and, for an engine that has them, the seed, the budget
// (0 keeps the engine's default) and the target.
template <class Options>
Options options_from(const OptionTable<Options>& table, const EngineSettings& settings) {
  Options o;
  read_options(table, settings.options, o);
  if constexpr (requires { o.seed; }) o.seed = settings.seed;
  if constexpr (requires { o.max_evaluations; })
    if (settings.max_evaluations != 0) o.max_evaluations = settings.max_evaluations;
  if constexpr (requires { o.target_objective; }) o.target_objective = settings.target_objective;
  return o;
}

// The registry entry of an engine class built from its Options: the listing
// from the table, and `make` reading the options with it (options_from).
template <class EngineClass, class Options>
EngineInfo engine_info(std::string name, std::string description, bool stochastic,
                       long default_evaluations, const OptionTable<Options>& (*table)()) {
  EngineInfo info;
  info.name = name;
  info.description = std::move(description);
  info.stochastic = stochastic;
  info.default_evaluations = default_evaluations;
  info.options = list_options(table());
  info.make = [name, table](const EngineSettings& settings) -> std::unique_ptr<Engine> {
    return std::make_unique<EngineClass>(options_from(table(), settings));
  };
  return info;
}

// The registry entries, one function per engine file, one line each in
// fit/engines/engines.def.
#define ENGINE(name) EngineInfo name##_engine_info();
#define ENGINE_FAMILY(name) std::vector<EngineInfo> name##_engine_infos();
#include "fit/engines/engines.def"
#undef ENGINE
#undef ENGINE_FAMILY

}  // namespace gyrotherm::fit
