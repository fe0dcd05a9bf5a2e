// gyrotherm.fit: `fit` on a path (the CLI's run, JSON and text) or on a
// mapping of arrays read in place (studies::run_fit on a fit::Table), with
// the averaged windows and the model at each for plotting and residuals.

#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "fit/model/terms.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"
#include "python/src/keywords.h"
#include "studies/fit/fit_run.h"
#include "studies/options/fit_options.h"

namespace gyrotherm::python {

namespace {

// The windows the model was fitted on, and the model at each.
py::dict windows_of(const studies::ChannelFit& c) {
  const fit::AveragedSeries& s = c.data.series;
  std::vector<double> model =
      fit::model_values(fit::design_matrix(c.data.derived, c.result.terms, c.result.parameters), c.result.coefficients);
  std::vector<double> residual(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) residual[k] = s.gyro_dph[k] - model[k];
  py::dict w;
  w["time_s"] = owning_array(std::vector<double>(s.time_s));
  w["temp_c"] = owning_array(std::vector<double>(s.temp_c));
  w["gyro_dph"] = owning_array(std::vector<double>(s.gyro_dph));
  w["model_dph"] = owning_array(std::move(model));
  w["residual_dph"] = owning_array(std::move(residual));
  return w;
}

py::dict fit(const Keywords& keywords, const py::object& columns, const py::object& truth_json) {
  const studies::FitRequest request = studies::fit_request(
      read_keywords(studies::fit_option_table(), columns.is_none() ? keywords : with_data(keywords, "arrays")));
  std::optional<studies::Truth> truth;
  if (!truth_json.is_none())
    truth = studies::truth_from_json(nlohmann::json::parse(truth_json.cast<std::string>()), "the record's truth");
  std::unique_ptr<TableHold> table;
  if (!columns.is_none()) table = table_of(columns, "arrays");
  studies::FitRun run;
  {
    py::gil_scoped_release free;
    run = table ? with_table_context(*table, [&] { return studies::run_fit(request, table->table, truth); })
                : studies::run_fit(request);
  }
  py::dict out;
  out["json"] = run.json;
  out["text"] = studies::fit_text(run);
  py::dict windows;
  for (const studies::ChannelFit& c : run.channels) windows[py::str(c.channel)] = windows_of(c);
  out["windows"] = windows;
  return out;
}

}  // namespace

void add_fitting(py::module_& m) {
  m.def("fit", &fit, py::arg("options"), py::arg("columns"), py::arg("truth"),
        "Fits the model: {'json': fit --json text, 'text': the report, 'windows': {channel: {name: array}}}.");
}

}  // namespace gyrotherm::python
