#pragma once
// Monte Carlo scoring of fitting engines (`gyrotherm score`).
//
// A campaign is N trials of one scenario. Trial k = 0 … N−1:
//
//  1. its seed is s_k = S + k (S: the campaign seed, by default the
//     scenario's), so trial k's record is `gyrotherm simulate SCENARIO
//     --seed s_k` when the scenario has no [spread];
//  2. the gyro's parameters are drawn from the scenario's [spread] table,
//     p = p₀·(1 + r·u), u ~ U(−1, 1) from make_rng(s_k, streams::score_spread), one
//     draw per key of sim::kSpreadKeys in that order (so a key's draw never
//     depends on which other keys are spread);
//  3. the scenario is simulated once with seed s_k (its thermal trace, which
//     depends on neither the seed nor [spread], is integrated once when the
//     campaign is set up and shared by all trials: sim::Simulator::record),
//     the record prepared once
//     (glitches, 100 s windows, regressors), and the exact least-squares
//     optimum σ* of the model computed (fit/engines/ols.h);
//  4. every engine fits the same problem with seed s_k, its budget, and the
//     target σ* (1 + ε), ε = 1e-6, at which it stops; recorded: whether and
//     after how many evaluations and seconds it reached the target, the final
//     gap σ/σ* − 1 (two-pass σ), the instability ratio σ_before/σ, the
//     absolute relative error of each coefficient against the trial's truth,
//     and the gap of the best σ so far at fixed evaluation counts (the
//     convergence curve).
//
// Trials are independent and carry their index, so they can run in any order
// on any thread or process; the scoreboard is built from the trials in index
// order, and is bit-identical for any thread or MPI rank count (only the
// fields named seconds* measure time).
//
// Statistics over the trials: studies/score/statistics.h; the scoreboard's
// files: studies/score/report.h; the baseline check: studies/score/baseline.h.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fit/engines/engine.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"
#include "sim/simulator.h"
#include "studies/score/statistics.h"

namespace gyrotherm::studies {

struct ScoreOptions {
  std::filesystem::path scenario;             // SCENARIO.toml (its rig and gyro files)
  std::vector<std::string> engines;           // empty: every registered engine
  std::string model = std::string(fit::kDefaultModel);  // formula of the fitted model
  long trials = 100;                          // N, at least 1
  std::optional<std::uint64_t> seed;          // S; absent: the scenario's seed
  long budget = 0;                            // evaluations of every seeded engine (0: its default)
  std::map<std::string, long> engine_budget;  // per engine, overrides `budget`
  std::map<std::string, std::map<std::string, std::string>> engine_options;  // engine → KEY=VALUE
  double target_relative = 1e-6;              // ε: the target is σ*·(1 + ε)
  fit::PipelineOptions pipeline;                   // preparation of the simulated record
  int curve_points_per_decade = 10;           // density of the convergence curves' grid
  // Throws InputError naming the field, the value and the rule.
  void validate() const;
  // The command line's --budget N or ENGINE=N, and --option ENGINE:KEY=VALUE
  // (fit/engines/engine.h parses the pair); throw InputError naming the text.
  void add_budget(const std::string& text);
  void add_engine_option(const std::string& text);
};

// One engine on one trial.
struct EngineTrial {
  bool reached = false;               // σ ≤ σ*·(1 + ε) at some evaluation
  long evaluations = 0;               // spent in all
  long evaluations_to_target = 0;     // the first evaluation at the target (0: not reached)
  double seconds = 0.0;               // the engine's run time (it stops at the target)
  double gap = 0.0;                   // σ/σ* − 1 at the end, two-pass σ
  double ratio = 0.0;                 // instability before / after
  fit::Termination termination = fit::Termination::budget_exhausted;
  std::vector<double> coefficient_error;  // |relative error| per Campaign::error_terms()
  std::vector<double> curve_gap;          // best-so-far gap at Campaign::curve_evaluations(); +∞ before the first
};

struct TrialOutcome {
  std::size_t index = 0;
  std::uint64_t seed = 0;
  std::string error;                  // non-empty: the trial failed with this message
  double before_dph = 0.0;            // instability of the raw 100 s means
  double optimum_dph = 0.0;           // σ*, two-pass
  std::vector<EngineTrial> engines;   // in Campaign::engines() order
  bool ok() const { return error.empty(); }
};


struct CurvePoint {
  long evaluations = 0;
  double q25 = 0.0, median = 0.0, q75 = 0.0;  // of the best-so-far gap; +∞: not every trial has started
};

struct EngineScore {
  std::string engine;
  bool stochastic = false;
  long budget = 0;                     // evaluations allowed (0: none, a closed form)
  std::size_t reached = 0;             // trials that reached the target
  double success_rate = 0.0;
  Range success_ci;
  Summary evaluations_to_target;       // +∞ where not reached
  Summary seconds_to_target;           // +∞ where not reached
  Summary seconds;                     // run time, reached or not
  Summary evaluations;                 // spent
  Summary gap;                         // final σ/σ* − 1
  Summary ratio;                       // instability before / after
  std::vector<Summary> coefficient_error;  // per Scoreboard::error_terms
  std::map<std::string, std::size_t> terminations;  // to_string(Termination) → trials
  std::vector<CurvePoint> curve;       // up to the first grid point at or past the last evaluation of any trial
};

struct Scoreboard {
  std::string scenario;                // its name
  std::string scenario_file;
  std::map<std::string, std::string> file_sha256;  // "scenario", "rig", "gyro"
  std::string model;
  std::size_t trials = 0;
  std::uint64_t seed = 0;              // S; trial k used S + k
  double target_relative = 0.0;
  std::map<std::string, double> spread;
  std::vector<std::string> error_terms;  // "1" and the model terms with a true value
  double before_median_dph = 0.0;
  double optimum_median_dph = 0.0;
  std::vector<EngineScore> engines;
  // How it ran (not part of the result): set by the caller.
  int threads = 1;
  int processes = 1;
  double seconds = 0.0;                // wall time of the campaign
};

// Progress, called once per finished trial, serialised (never concurrently).
class ScoreObserver {
 public:
  virtual ~ScoreObserver() = default;
  virtual void on_trial_done(std::size_t done, std::size_t total) = 0;
};

class Campaign {
 public:
  // Loads and checks the scenario, rig, gyro, model, engines and their
  // settings (throws InputError before any trial runs), then integrates the
  // thermal trace (sim::SolverError if CVODE fails).
  explicit Campaign(ScoreOptions options);

  std::size_t trials() const { return static_cast<std::size_t>(options_.trials); }
  std::uint64_t seed() const { return seed_; }
  std::uint64_t trial_seed(std::size_t k) const { return seed_ + k; }
  const std::vector<std::string>& engines() const { return engine_names_; }
  const std::vector<std::string>& error_terms() const { return error_terms_; }
  const std::vector<long>& curve_evaluations() const { return curve_grid_; }
  const ScoreOptions& options() const { return options_; }
  // The settings engine e gets in trial k.
  fit::EngineSettings settings(std::size_t e, std::size_t k, double target_objective) const;

  // Steps 1–4 for trial k. A failure is reported in TrialOutcome::error.
  TrialOutcome run_trial(std::size_t k) const;
  // The trials `indices` on `threads` threads (each takes the next
  // unstarted trial); the outcomes come back in the order of `indices`.
  std::vector<TrialOutcome> run(std::span<const std::size_t> indices, int threads,
                                ScoreObserver* observer = nullptr) const;
  // The scoreboard of all N outcomes, in any order. Throws InputError if
  // one is missing or failed (naming the trial and its seed).
  Scoreboard summarize(std::vector<TrialOutcome> outcomes) const;

 private:
  ScoreOptions options_;
  sim::Scenario scenario_;
  sim::RigConfig rig_;
  sim::GyroConfig gyro_;
  std::vector<const fit::Term*> terms_;
  std::vector<const fit::EngineInfo*> infos_;
  std::vector<std::string> engine_names_;
  std::vector<long> budgets_;
  std::vector<std::string> error_terms_;
  std::vector<long> curve_grid_;
  std::uint64_t seed_ = 0;
  sim::ThermalTrace trace_;  // the temperatures every trial shares
};

}  // namespace gyrotherm::studies
