// gyrotherm engines [--json]   the fitting engines and their options
// gyrotherm effects [--json]   the model terms (physical effects)

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "fit/engines/engine.h"
#include "sim/effects/effect.h"

namespace gyrotherm::app {
namespace {

int run_engines(bool json) {
  if (json) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const fit::EngineInfo& e : fit::engine_registry()) {
      nlohmann::ordered_json options = nlohmann::ordered_json::object();
      for (const fit::OptionInfo& o : e.options) options[o.key] = o.line();
      j.push_back({{"name", e.name},
                   {"description", e.description},
                   {"stochastic", e.stochastic},
                   {"default_evaluations", e.default_evaluations},
                   {"options", options}});
    }
    fmt::print("{}\n", nlohmann::ordered_json{{"engines", j}}.dump());
    return 0;
  }
  for (const fit::EngineInfo& e : fit::engine_registry()) {
    fmt::print("{:<9} {}{}\n", e.name, e.description, e.stochastic ? " [seeded]" : "");
    for (const fit::OptionInfo& o : e.options) fmt::print("          --option {}=  {}\n", o.key, o.line());
  }
  return 0;
}

int run_effects(bool json) {
  if (json) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const effects::Effect* t : effects::registry()) {
      nlohmann::ordered_json e = {{"term", t->name},
                                  {"meaning", t->meaning},
                                  {"unit", t->unit},
                                  {"needs", t->needs_temp2() ? "temp2_c" : "temp_c"},
                                  {"columns", t->column_names()},
                                  {"coefficient_unit", t->coefficient_unit()},
                                  {"simulator", t->hidden() ? "[hidden] " + std::string(t->name)
                                                            : "[truth] " + std::string(t->truth_key)}};
      if (t->parameter)
        e["parameter"] = {{"name", t->parameter->name},
                          {"lower", t->parameter->lower},
                          {"upper", t->parameter->upper},
                          {"gyro_key", t->parameter->gyro_key},
                          {"simulator_default", t->parameter->simulator_default}};
      j.push_back(e);
    }
    fmt::print("{}\n", nlohmann::ordered_json{{"effects", j}}.dump());
    return 0;
  }
  for (const effects::Effect* t : effects::registry()) {
    std::string extra = t->needs_temp2() ? "  (needs temp2_c)" : "";
    if (t->parameter)
      extra += fmt::format("  ({} fitted in [{:g}, {:g}])", t->parameter->name, t->parameter->lower,
                           t->parameter->upper);
    fmt::print("{:<7} {:<8} {}{}\n", t->name, t->unit, t->meaning, extra);
  }
  fmt::print("\nSimulate a hidden effect with 'gyrotherm simulate ... --hidden TERM=COEF' (TERM one of "
             "{}); its parameter, if any, is set in the gyro file's [hidden] table.\n",
             effects::hidden_names());
  return 0;
}

}  // namespace

void add_registry_commands(CLI::App& app, Run* run) {
  auto engines_json = std::make_shared<bool>(false);
  CLI::App* engines = app.add_subcommand("engines", "List the fitting engines and their options");
  engines->add_flag("--json", *engines_json, "Print one JSON object");
  engines->callback([engines_json, run] { *run = [engines_json] { return run_engines(*engines_json); }; });

  auto effects_json = std::make_shared<bool>(false);
  CLI::App* effects = app.add_subcommand("effects", "List the model terms (physical effects)");
  effects->add_flag("--json", *effects_json, "Print one JSON object");
  effects->callback([effects_json, run] { *run = [effects_json] { return run_effects(*effects_json); }; });
}

}  // namespace gyrotherm::app
