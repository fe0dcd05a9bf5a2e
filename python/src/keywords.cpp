#include "python/src/keywords.h"

#include <fmt/format.h>

#include "sim/util/input_error.h"
#include "studies/options/option_reference.h"

namespace gyrotherm::python {

namespace py = pybind11;

Keywords with_data(Keywords keywords, const std::string& name) {
  keywords.insert(keywords.begin(), {"data", name});
  return keywords;
}

py::list option_rows(const std::string& command) {
  // Every command with a table but the two that are campaigns, not calls on a record.
  const studies::CommandOptions* listed = studies::command_options(command);
  if (listed == nullptr || command == "reproduce" || command == "score")
    throw InputError(fmt::format("options('{}'): expected one of fit, diagnose, allan, compensate, export, "
                                 "simulate, plan, check, report", command));
  const std::vector<OptionInfo>& rows = listed->rows;
  py::list out;
  for (const OptionInfo& r : rows) {
    if (r.keyword == "json") continue;  // every result has to_json()
    py::dict d;
    d["keyword"] = r.keyword;
    d["flag"] = r.names;
    d["help"] = shown_help(r);
    d["default"] = r.default_value;
    d["kind"] = std::string(kind_name(r.kind));
    d["required"] = r.required;
    out.append(d);
  }
  return out;
}

}  // namespace gyrotherm::python
