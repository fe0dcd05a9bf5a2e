#include "studies/options/plan_options.h"

#include <fmt/format.h>

#include "fit/model/formula.h"
#include "sim/util/comma_list.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {
// Named so that the unity batches can join the option files (each has its O).
namespace plan_rows_of {

using O = PlanCommandOptions;
using R = plan::PlanRequest;

// A row of the request's `field`. Its lists the command line also takes as
// one comma list (--se T=1,dT=2), as --range its two numbers (-20,50 or -20 50).
template <class Field>
OptionRow<O> row(std::string names, std::string help, Field field) {
  if constexpr (std::is_same_v<Field, std::vector<double> O::*>) {
    OptionRow<O> r{names, keyword_of(names), std::move(help), OptionKind::list, false, {}, "FLOAT x 2"};
    r.several_per_name = true;
    r.set = [field, names](O& o, const std::string& v) {
      for (const std::string& item : split_commas(v)) (o.*field).push_back(parse_number(names, item));
    };
    return r;
  } else {
    OptionRow<O> r = nested_row(std::move(names), std::move(help), &O::request, field);
    if constexpr (std::is_same_v<Field, std::vector<std::string> R::*>)
      r.set = [field](O& o, const std::string& v) {
        for (const std::string& item : split_commas(v)) (o.request.*field).push_back(item);
      };
    return r;
  }
}

std::vector<OptionRow<O>> plan_rows() {
  return {
      defaulting(row("--model", "The model to identify", &R::model),
                 detail::quoted_if_spaced(std::string(fit::kDefaultModel))),
      row("--se", "Standard error wanted, TERM=VALUE in the coefficient's unit", &R::se),
      row("--rel-se", "Standard error wanted as a fraction of the prior: F (every term) or TERM=F", &R::rel_se),
      row("--separate", "Terms to tell apart, NAME or NAME=SIZE (prior coefficient), or a diagnose --json file",
          &R::separate),
      defaulting(row("--prior", "A coefficient's prior value, TERM=VALUE", &R::prior), "the gyro file's"),
      row("--param", "A nonlinear term's parameter, TERM=VALUE (e.g. lag=1200)", &R::param),
      defaulting(row("--scenario", "Room, start temperature, rig and gyro", &R::scenario), "scenarios/cycle.toml"),
      row("--rig", "Rig file instead of the scenario's", &R::rig),
      row("--gyro", "Gyro file (truth, priors and noise) instead of the scenario's", &R::gyro),
      row("--noise", "The noise (and priors) of a fit, diagnose or allan --json", &R::noise),
      with_rule(row("--tau", "A first-order thermal path of TAU s from chamber to sensor instead of a rig", &R::tau_s),
                number_above(0.0, kNoBound, "s")),
      defaulting(row("--range", "Chamber range LO,HI in °C", &O::range),
                 "the scenario's set points"),
      with_rule(defaulting(row("--max-rate", "Fastest ramp, °C/min", &R::max_rate_c_per_min), "the scenario's fastest"),
                number_above(0.0, kNoBound, "°C/min")),
      with_rule(row("--min-soak", "Shortest soak, s", &R::min_soak_s), number_in(0.0, kNoBound, "s")),
      with_rule(row("--longest", "Longest test considered, h", &R::longest_h), number_above(0.0, 720.0, "h")),
      row("--out", "Folder for plan.toml, rig.toml, gyro.toml, plan_setpoint.csv, plan.png", &R::out),
      row("--verify", "Simulate and fit the planned test N times; report achieved errors", &R::verify),
      defaulting(row("--seed", "First seed of --verify", &R::seed), "the scenario's"),
      field_row<O>("--json", "Print one JSON object", &O::json)};
}

}  // namespace plan_rows_of

const OptionTable<PlanCommandOptions>& plan_option_table() {
  static const OptionTable<PlanCommandOptions> table{"plan", plan_rows_of::plan_rows()};
  return table;
}

plan::PlanRequest plan_request(const PlanCommandOptions& o, const std::string& default_scenario) {
  check_rules(plan_option_table(), o);  // --tau, --max-rate, --min-soak, --longest
  plan::PlanRequest request = o.request;
  if (request.scenario.empty()) request.scenario = default_scenario;
  if (!o.range.empty()) {
    if (o.range.size() != 2)
      throw InputError(fmt::format("--range {}: expected two numbers LO,HI in °C", fmt::join(o.range, ",")));
    request.range_c = {o.range[0], o.range[1]};
  }
  return request;
}

}  // namespace gyrotherm::studies
