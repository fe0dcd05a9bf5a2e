// gyrotherm plan [--model M] [--se T=V,…] [--rel-se [T=]F,…] [--separate A[=S],B… | DIAGNOSE.json]
//   [--prior T=V,…] [--param T=V,…] [--scenario F] [--rig F] [--gyro F] [--noise F.json] [--tau S]
//   [--range LO,HI] [--max-rate R] [--min-soak S] [--longest H] [--out DIR] [--verify N] [--seed N] [--json]
// (studies/options/plan_options.h, studies/plan/plan.h)

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "app/progress.h"
#include "studies/options/plan_options.h"

namespace gyrotherm::app {
namespace {

int run_plan(const studies::PlanCommandOptions& o) {
  const auto request = studies::plan_request(o, default_scenarios_dir() + "/cycle.toml");
  auto bar = step_progress();
  std::string last;  // a line per stage and tenth, not per step
  studies::plan::PlanProgress progress{[&](const std::string& stage, int done, int total) {
    const std::string now = fmt::format("{} {}", stage, total > 0 ? 10 * done / total : 10);
    if (now == last) return;
    last = now;
    bar(fmt::format("{} {}/{}", stage, done, total), total > 0 ? static_cast<double>(done) / total : 1.0);
  }};
  const studies::plan::PlanResult r = studies::plan::run_plan(request, progress);
  fmt::print("{}", o.json ? studies::plan::plan_json(r).dump() + "\n" : studies::plan::plan_text(r));
  return 0;
}

}  // namespace

void add_plan_command(CLI::App& app, Run* run) {
  add_table_command<studies::PlanCommandOptions>(app, run, "plan", "Design the shortest chamber test that identifies a model to the precision wanted", studies::plan_option_table(), run_plan);
}

}  // namespace gyrotherm::app
