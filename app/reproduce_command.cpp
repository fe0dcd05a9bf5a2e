// gyrotherm reproduce [--out DIR] [--scenarios DIR] [--engines LIST] [--seed N] [--json]
// The main job: the paper's Table 1 scenarios on the default simulated gyro,
// side by side with the paper's figures (studies/reproduce/reproduce.h).

#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "app/progress.h"
#include "studies/options/reproduce_options.h"
#include "studies/reproduce/report.h"

namespace gyrotherm::app {
namespace {

int run_reproduce(const studies::ReproduceCommandOptions& o) {
  studies::ReproduceOptions options = studies::reproduce_request(o, default_scenarios_dir());
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
  add_table_command<studies::ReproduceCommandOptions>(app, run, "reproduce",
                                                       "Reproduce the paper's Table 1 on the simulated gyro (the main job)",
                                                       studies::reproduce_option_table(), run_reproduce);
}

}  // namespace gyrotherm::app
