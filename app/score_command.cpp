// gyrotherm score SCENARIO.toml [--engines LIST] [--trials N] [--threads N] [--seed S]
//                [--model F] [--budget N | ENGINE=N ...] [--option ENGINE:KEY=VALUE ...]
//                [--baseline B.json] [--json] [--out DIR]
// A Monte Carlo campaign scoring the fitting engines (studies/score/campaign.h); under
// mpirun the trials are spread over the ranks (app/score_mpi.h).

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <thread>

#include "app/progress.h"
#include "sim/util/comma_list.h"
#include "app/option_binding.h"
#include "app/score_mpi.h"
#include "studies/score/baseline.h"
#include "studies/score/campaign.h"
#include "studies/score/outcome_packing.h"
#include "studies/score/report.h"
#include "sim/util/input_error.h"

namespace gyrotherm::app {
namespace {

struct ScoreCli {
  std::string scenario;
  std::string engines;
  long trials = 100;
  int threads = 0;
  std::uint64_t seed = 0;
  const CLI::Option* seed_option = nullptr;  // given?
  std::string model = std::string(fit::kDefaultModel);
  std::vector<std::string> budgets;
  std::vector<std::string> engine_options;
  std::string baseline;
  std::string out;
  bool json = false;
};

studies::ScoreOptions score_options(const ScoreCli& o) {
  studies::ScoreOptions s;
  s.scenario = o.scenario;
  s.engines = split_commas(o.engines);
  s.model = o.model;
  s.trials = o.trials;
  if (o.seed_option != nullptr && given(o.seed_option)) s.seed = o.seed;
  for (const std::string& b : o.budgets) s.add_budget(b);
  for (const std::string& kv : o.engine_options) s.add_engine_option(kv);
  return s;
}

// Rank 0's part after the trials: files, the baseline check, the report.
int report(const studies::Scoreboard& board, const std::optional<studies::Baseline>& baseline, const ScoreCli& o) {
  const std::string json = studies::scoreboard_json(board);
  std::vector<std::string> written;
  if (!o.out.empty()) {
    written = studies::write_score_files(o.out, board);
  }
  studies::BaselineComparison check;
  if (baseline) check = studies::compare_to_baseline(board, *baseline);

  if (o.json) {
    fmt::print("{}", json);
  } else {
    fmt::print("{}", studies::score_text(board));
    for (const std::string& f : written) fmt::print("wrote {}\n", f);
  }
  for (const std::string& note : check.notes) fmt::print(stderr, "gyrotherm: score: note: {}\n", note);
  if (!baseline) return 0;
  if (check.passed()) {
    if (!o.json) fmt::print("baseline {}: no engine is worse beyond Monte Carlo noise\n", o.baseline);
    return 0;
  }
  for (const studies::Regression& r : check.regressions)
    fmt::print(stderr, "gyrotherm: score: worse than the baseline {}: {}\n", o.baseline, r.message);
  return 1;
}

int run_score(const ScoreCli& o) {
  std::optional<ScoreMpi> mpi_holder;
  try {
    mpi_holder.emplace();
  } catch (const InputError&) {
    if (ScoreMpi::launcher_rank() != 0) return 2;  // one rank reports it
    throw;
  }
  const ScoreMpi& mpi = *mpi_holder;

  // Set-up, identical on every rank: a bad input fails everywhere at once.
  std::optional<studies::Campaign> campaign;
  std::optional<studies::Baseline> baseline;
  int threads = o.threads;
  try {
    if (o.threads < 0 || o.threads > 1024)
      throw InputError(fmt::format("--threads {}: must be from 1 to 1024 (0: one per core)", o.threads));
    campaign.emplace(score_options(o));
    if (!o.baseline.empty()) baseline = studies::load_baseline(o.baseline);
    if (threads == 0)
      threads = mpi.size() > 1 ? 1 : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  } catch (...) {
    if (!mpi.root()) return 2;
    throw;
  }

  // The trials of this rank: k ≡ rank (mod size).
  std::vector<std::size_t> mine;
  for (auto k = static_cast<std::size_t>(mpi.rank()); k < campaign->trials(); k += static_cast<std::size_t>(mpi.size()))
    mine.push_back(k);
  TrialProgress progress(mpi.size() > 1 ? fmt::format("score (rank 0 of {})", mpi.size()) : std::string("score"));
  const auto started = std::chrono::steady_clock::now();
  const std::vector<studies::TrialOutcome> outcomes = campaign->run(mine, threads, mpi.root() ? &progress : nullptr);
  const std::vector<std::string> parts = mpi.gather(studies::pack_outcomes(outcomes));

  int code = 0;
  std::exception_ptr failure;
  if (mpi.root()) {
    try {
      std::vector<studies::TrialOutcome> all;
      for (const std::string& part : parts)
        for (studies::TrialOutcome& t : studies::unpack_outcomes(part)) all.push_back(std::move(t));
      studies::Scoreboard board = campaign->summarize(std::move(all));
      board.threads = threads;
      board.processes = mpi.size();
      board.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      code = report(board, baseline, o);
    } catch (...) {
      failure = std::current_exception();
      code = 2;
    }
  }
  code = mpi.broadcast(code);  // every rank exits alike
  if (failure) std::rethrow_exception(failure);
  return code;
}

}  // namespace

void add_score_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<ScoreCli>();
  CLI::App* cmd = add_subcommand(
      app, "score",
      "Monte Carlo campaign scoring the fitting engines on a scenario (also under mpirun)");
  require(add_value(cmd, "scenario", o->scenario,
                    "Scenario TOML (its [spread] table, if any, varies the gyro per trial)"));
  add_value(cmd, "--engines", o->engines, "Comma-separated engines (default: all)");
  add_value(cmd, "--trials", o->trials, "Number of trials N (default 100)");
  add_value(cmd, "--threads", o->threads, "Threads per process (default: one per core; 1 under mpirun)");
  o->seed_option = add_value(cmd, "--seed", o->seed, "Campaign seed S; trial k uses S + k (default: the scenario's seed)");
  add_value(cmd, "--model", o->model, "Model formula (default 'T + T^2 + dT')");
  add_value(cmd, "--budget", o->budgets,
            "Evaluation budget: N for every seeded engine, or ENGINE=N (repeatable; 0: the engine's default)");
  add_value(cmd, "--option", o->engine_options, "Engine option ENGINE:KEY=VALUE (repeatable)");
  add_value(cmd, "--baseline", o->baseline,
            "A saved 'score --json': exit 1 naming engine and metric where an engine is worse beyond "
            "Monte Carlo noise");
  add_value(cmd, "--out", o->out,
            "Write scoreboard.json, scoreboard.md, convergence.csv and convergence.png here "
            "(default: no files)");
  add_flag(cmd, "--json", o->json, "Print the scoreboard as one JSON object");
  when_chosen(cmd, run, [o] { return run_score(*o); });
}

}  // namespace gyrotherm::app
