// gyrotherm reproduce [--out DIR] [--scenarios DIR] [--engines LIST] [--seed N] [--json]
// The main job: the paper's Table 1 scenarios on the default simulated gyro,
// side by side with the paper's figures (studies/reproduce/reproduce.h).

#include <fmt/core.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "app/progress.h"
#include "sim/util/comma_list.h"
#include "studies/reproduce/report.h"

namespace gyrotherm::app {
namespace {

struct ReproduceCli {
  std::string out = "results";
  std::string scenarios;
  std::string engines;
  std::uint64_t seed = 1;
  bool json = false;
};


int run_reproduce(const ReproduceCli& o) {
  const std::string dir = o.scenarios.empty() ? default_scenarios_dir() : o.scenarios;
  studies::ReproduceOptions options;
  options.cycle = dir + "/cycle.toml";
  options.test1 = dir + "/random.toml";
  options.test2 = dir + "/warmup.toml";
  options.engines = split_commas(o.engines);
  options.engine_seed = o.seed;
  options.progress = step_progress();
  const auto started = std::chrono::steady_clock::now();
  const studies::ReproduceResult r = studies::reproduce(options);
  const nlohmann::ordered_json j = studies::write_reproduce_report(o.out, r, started, options.progress);
  fmt::print("{}", o.json ? j.dump() + "\n" : studies::reproduce_text(r, o.out, j["total_seconds"].get<double>()));
  return 0;
}

}  // namespace

std::string default_scenarios_dir() {
  if (std::filesystem::exists("scenarios/cycle.toml")) return "scenarios";
  return std::string(GYROTHERM_SOURCE_DIR) + "/scenarios";
}

void add_reproduce_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<ReproduceCli>();
  CLI::App* cmd = add_subcommand(app, "reproduce", "Reproduce the paper's Table 1 on the simulated gyro (the main job)");
  add_value(cmd, "--out", o->out, "Output folder (default results)");
  add_value(cmd, "--scenarios", o->scenarios, "Folder with cycle.toml, random.toml, warmup.toml (default scenarios/)");
  add_value(cmd, "--engines", o->engines, "Comma-separated engines (default: all)");
  add_value(cmd, "--seed", o->seed, "Seed of the stochastic engines (default 1)");
  add_flag(cmd, "--json", o->json, "Print table1.json, with the run times, on stdout");
  when_chosen(cmd, run, [o] { return run_reproduce(*o); });
}

}  // namespace gyrotherm::app
