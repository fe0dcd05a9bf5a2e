// gyrotherm reproduce [--out DIR] [--scenarios DIR] [--engines LIST] [--seed N] [--json]
// The main job: the paper's Table 1 scenarios on the default simulated gyro,
// side by side with the paper's figures (studies/reproduce/reproduce.h).

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/util/comma_list.h"
#include "app/commands.h"
#include "studies/reproduce/report.h"
#include "sim/util/input_error.h"

namespace gyrotherm::app {
namespace {

struct ReproduceCli {
  std::string out = "results";
  std::string scenarios;
  std::string engines;
  std::uint64_t seed = 1;
  bool json = false;
};

std::string default_scenarios_dir() {
  if (std::filesystem::exists("scenarios/cycle.toml")) return "scenarios";
  return std::string(GYROTHERM_SOURCE_DIR) + "/scenarios";
}

int run_reproduce(const ReproduceCli& o) {
  const std::string dir = o.scenarios.empty() ? default_scenarios_dir() : o.scenarios;
  studies::ReproduceOptions options;
  options.cycle = dir + "/cycle.toml";
  options.test1 = dir + "/random.toml";
  options.test2 = dir + "/warmup.toml";
  options.engines = split_commas(o.engines);
  options.engine_seed = o.seed;
  const bool tty = ::isatty(2) != 0;
  options.progress = [tty](const std::string& step, double f) {
    if (tty)
      fmt::print(stderr, "\r[{:3.0f}%] {:<50}", 100.0 * f, step);
    else
      fmt::print(stderr, "[{:3.0f}%] {}\n", 100.0 * f, step);
    if (tty && f >= 1.0) fmt::print(stderr, "\n");
  };
  const auto started = std::chrono::steady_clock::now();
  const studies::ReproduceResult r = studies::reproduce(options);

  options.progress("drawing the figures", 1.0);
  const nlohmann::ordered_json j = studies::write_reproduce_report(o.out, r, started);
  const double total = j["total_seconds"].get<double>();

  if (o.json) {
    fmt::print("{}\n", j.dump());
    return 0;
  }
  const studies::PaperFigures paper;
  fmt::print("Table 1, side by side (instability of 100 s means, °/h):\n");
  fmt::print("  cycle  raw      paper {:.5f}  ours {:.5f}\n", paper.cycle_raw, r.cycle_raw_dph);
  for (const auto& e : r.engines)
    fmt::print("  cycle  {:<8} {}  ours {:.5f} ({:.2f}x)\n", e.engine,
               e.engine == "stepwise" ? fmt::format("paper {:.5f}", paper.cycle_stepwise)
               : e.engine == "iafsa"  ? fmt::format("paper {:.5f}", paper.cycle_iafsa)
                                      : std::string(17, ' '),
               e.fit.instability_after_dph, e.fit.ratio());
  const std::string best = studies::shown_engine(r);
  fmt::print("  test 1 paper {:.5f} -> {:.5f} ({:.2f}x)  ours ({}) {:.5f} -> {:.5f} ({:.2f}x)\n", paper.test1_before,
             paper.test1_after, paper.test1_times, best, r.test1.before_dph, r.test1.by_engine.at(best).after_dph,
             r.test1.by_engine.at(best).ratio());
  fmt::print("  test 2 paper {:.5f} -> {:.5f} ({:.2f}x)  ours ({}) {:.5f} -> {:.5f} ({:.2f}x)\n", paper.test2_before,
             paper.test2_after, paper.test2_times, best, r.test2.before_dph, r.test2.by_engine.at(best).after_dph,
             r.test2.by_engine.at(best).ratio());
  fmt::print("wrote {0}/table1.md, {0}/table1.json and figures in {1:.1f} s\n", o.out, total);
  return 0;
}

}  // namespace

void add_reproduce_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<ReproduceCli>();
  CLI::App* cmd = app.add_subcommand("reproduce", "Reproduce the paper's Table 1 on the simulated gyro (the main job)");
  cmd->add_option("--out", o->out, "Output folder (default results)");
  cmd->add_option("--scenarios", o->scenarios, "Folder with cycle.toml, random.toml, warmup.toml (default scenarios/)");
  cmd->add_option("--engines", o->engines, "Comma-separated engines (default: all)");
  cmd->add_option("--seed", o->seed, "Seed of the stochastic engines (default 1)");
  cmd->add_flag("--json", o->json, "Print table1.json on stdout");
  cmd->callback([o, run] { *run = [o] { return run_reproduce(*o); }; });
}

}  // namespace gyrotherm::app
