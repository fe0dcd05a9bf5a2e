// gyrotherm plan [--model M] [--se T=V,…] [--rel-se [T=]F,…] [--separate A[=S],B… | DIAGNOSE.json]
//   [--prior T=V,…] [--param T=V,…] [--scenario F] [--rig F] [--gyro F] [--noise F.json] [--tau S]
//   [--range LO,HI] [--max-rate R] [--min-soak S] [--longest H] [--out DIR] [--verify N] [--seed N] [--json]
// (studies/plan/plan.h)

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "app/progress.h"
#include "studies/plan/plan.h"

namespace gyrotherm::app {
namespace {

struct PlanCli {
  studies::plan::PlanRequest request;
  std::vector<double> range;
  bool json = false;
};

int run_plan(PlanCli o) {
  auto& rq = o.request;
  if (rq.scenario.empty()) rq.scenario = default_scenarios_dir() + "/cycle.toml";
  if (!o.range.empty()) rq.range_c = {o.range[0], o.range[1]};
  auto bar = step_progress();
  std::string last;  // a line per stage and tenth, not per step
  studies::plan::PlanProgress progress{[&](const std::string& stage, int done, int total) {
    const std::string now = fmt::format("{} {}", stage, total > 0 ? 10 * done / total : 10);
    if (now == last) return;
    last = now;
    bar(fmt::format("{} {}/{}", stage, done, total), total > 0 ? static_cast<double>(done) / total : 1.0);
  }};
  const studies::plan::PlanResult r = studies::plan::run_plan(rq, progress);
  fmt::print("{}", o.json ? studies::plan::plan_json(r).dump() + "\n" : studies::plan::plan_text(r));
  return 0;
}

}  // namespace

void add_plan_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<PlanCli>();
  auto& rq = o->request;
  CLI::App* cmd = app.add_subcommand(
      "plan", "Design the shortest chamber test that identifies a model to the precision wanted");
  cmd->add_option("--model", rq.model, "The model to identify (default \"T + T^2 + dT\")");
  cmd->add_option("--se", rq.se, "Standard error wanted, TERM=VALUE in the coefficient's unit")->delimiter(',');
  cmd->add_option("--rel-se", rq.rel_se, "Standard error wanted as a fraction of the prior: F (every term) or TERM=F")
      ->delimiter(',');
  cmd->add_option("--separate", rq.separate,
                  "Terms to tell apart, NAME or NAME=SIZE (prior coefficient), or a diagnose --json file")
      ->delimiter(',');
  cmd->add_option("--prior", rq.prior, "A coefficient's prior value, TERM=VALUE (default: the gyro file's)")
      ->delimiter(',');
  cmd->add_option("--param", rq.param, "A nonlinear term's parameter, TERM=VALUE (e.g. lag=1200)")->delimiter(',');
  cmd->add_option("--scenario", rq.scenario, "Room, start temperature, rig and gyro (default scenarios/cycle.toml)");
  cmd->add_option("--rig", rq.rig, "Rig file instead of the scenario's");
  cmd->add_option("--gyro", rq.gyro, "Gyro file (truth, priors and noise) instead of the scenario's");
  cmd->add_option("--noise", rq.noise, "The noise (and priors) of a fit, diagnose or allan --json");
  cmd->add_option("--tau", rq.tau_s, "A first-order thermal path of TAU s from chamber to sensor instead of a rig");
  cmd->add_option("--range", o->range, "Chamber range LO,HI in °C (default: the scenario's set points)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--max-rate", rq.max_rate_c_per_min, "Fastest ramp, °C/min (default: the scenario's fastest)");
  cmd->add_option("--min-soak", rq.min_soak_s, "Shortest soak, s (default 0)");
  cmd->add_option("--longest", rq.longest_h, "Longest test considered, h (default 72)");
  cmd->add_option("--out", rq.out, "Folder for plan.toml, rig.toml, gyro.toml, plan_setpoint.csv, plan.png (default plan)");
  cmd->add_option("--verify", rq.verify, "Simulate and fit the planned test N times; report achieved errors");
  cmd->add_option("--seed", rq.seed, "First seed of --verify (default: the scenario's)");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  when_chosen(cmd, run, [o] { return run_plan(*o); });
}

}  // namespace gyrotherm::app
