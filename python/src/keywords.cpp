#include "python/src/keywords.h"

#include <fmt/format.h>

#include "sim/util/input_error.h"
#include "studies/options/allan_options.h"
#include "studies/options/check_options.h"
#include "studies/options/report_options.h"
#include "studies/options/compensate_options.h"
#include "studies/options/diagnose_options.h"
#include "studies/options/export_options.h"
#include "studies/options/fit_options.h"
#include "studies/options/plan_options.h"
#include "studies/options/simulate_options.h"

namespace gyrotherm::python {

namespace py = pybind11;

Keywords with_data(Keywords keywords, const std::string& name) {
  keywords.insert(keywords.begin(), {"data", name});
  return keywords;
}

py::list option_rows(const std::string& command) {
  std::vector<studies::OptionInfo> rows;
  if (command == "fit") rows = studies::list_options(studies::fit_option_table());
  else if (command == "diagnose") rows = studies::list_options(studies::diagnose_option_table());
  else if (command == "allan") rows = studies::list_options(studies::allan_option_table());
  else if (command == "compensate") rows = studies::list_options(studies::compensate_option_table());
  else if (command == "export") rows = studies::list_options(studies::export_option_table());
  else if (command == "simulate") rows = studies::list_options(studies::simulate_option_table());
  else if (command == "plan") rows = studies::list_options(studies::plan_option_table());
  else if (command == "check") rows = studies::list_options(studies::check_option_table());
  else if (command == "report") rows = studies::list_options(studies::report_option_table());
  else
    throw InputError(fmt::format("options('{}'): expected one of fit, diagnose, allan, compensate, export, "
                                 "simulate, plan, check, report", command));
  py::list out;
  for (const studies::OptionInfo& r : rows) {
    if (r.keyword == "json") continue;  // every result has to_json()
    py::dict d;
    d["keyword"] = r.keyword;
    d["flag"] = r.names;
    d["help"] = studies::shown_help(r);
    d["default"] = r.default_value;
    d["kind"] = std::string(studies::kind_name(r.kind));
    d["required"] = r.required;
    out.append(d);
  }
  return out;
}

}  // namespace gyrotherm::python
