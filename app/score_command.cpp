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
#include "app/option_binding.h"
#include "app/score_mpi.h"
#include "studies/score/baseline.h"
#include "studies/options/score_options.h"
#include "studies/score/campaign.h"
#include "studies/score/outcome_packing.h"
#include "studies/score/report.h"
#include "sim/util/input_error.h"

namespace gyrotherm::app {
namespace {

// Rank 0's part after the trials: files, the baseline check, the report.
int report(const studies::Scoreboard& board, const std::optional<studies::Baseline>& baseline, const studies::ScoreCommandOptions& o) {
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
  for (const studies::BaselineNote& note : check.notes)
    fmt::print(stderr, "gyrotherm: score: note: {}\n", studies::baseline_note_text(note));
  if (!baseline) return 0;
  if (check.passed()) {
    if (!o.json) fmt::print("baseline {}: no engine is worse beyond Monte Carlo noise\n", o.baseline);
    return 0;
  }
  for (const studies::Regression& r : check.regressions)
    fmt::print(stderr, "gyrotherm: score: worse than the baseline {}: {}\n", o.baseline, studies::regression_text(r));
  return 1;
}

int run_score(const studies::ScoreCommandOptions& o) {
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
    campaign.emplace(studies::score_request(o));
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
  add_table_command<studies::ScoreCommandOptions>(
      app, run, "score", "Monte Carlo campaign scoring the fitting engines on a scenario (also under mpirun)",
      studies::score_option_table(), run_score);
}

}  // namespace gyrotherm::app
