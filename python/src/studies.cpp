// gyrotherm.diagnose, allan, compensate, export, plan: each command's run on
// a path or on arrays (a fit::Table over them), its JSON and its text; a fit
// given as a FitResult arrives as its JSON text and is read as a fit file is.

#include <pybind11/stl.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "fit/fit_file.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"
#include "python/src/keywords.h"
#include "studies/allan/allan_study.h"
#include "studies/check/check_run.h"
#include "studies/diagnose/diagnose_run.h"
#include "studies/export/exporter.h"
#include "studies/fit/compensate_run.h"
#include "studies/options/allan_options.h"
#include "studies/options/check_options.h"
#include "studies/options/report_options.h"
#include "studies/options/compensate_options.h"
#include "studies/options/diagnose_options.h"
#include "studies/options/export_options.h"
#include "studies/options/plan_options.h"
#include "studies/plan/plan.h"

namespace gyrotherm::python {

namespace {

// A fit given in memory is named fit::kFitInMemory in reports (a fit file's path otherwise).
using fit::kFitInMemory;

py::dict report(const std::string& json, const std::string& text) {
  py::dict out;
  out["json"] = json;
  out["text"] = text;
  return out;
}

// The fits of a FitResult's JSON text, read as a fit file's.
std::vector<fit::SavedFit> fits_of(const py::object& fit_json) {
  if (fit_json.is_none()) return {};
  return fit::load_fits_json(nlohmann::json::parse(fit_json.cast<std::string>()), kFitInMemory);
}

std::unique_ptr<TableHold> table_or_none(const py::object& columns) {
  return columns.is_none() ? nullptr : table_of(columns, "arrays");
}

Keywords for_record(const Keywords& keywords, const py::object& columns) {
  return columns.is_none() ? keywords : with_data(keywords, "arrays");
}

// The request of a command that reads a record and a fit (allan,
// compensate): a fit given in memory is named kFitInMemory and handed over
// read, in place of a file.
template <class Options, class Request>
Request with_fit(const OptionTable<Options>& table, Request (*request_of)(const Options&),
                 const Keywords& keywords, const py::object& columns, const py::object& fit_json) {
  Keywords given = for_record(keywords, columns);
  std::vector<fit::SavedFit> fits = fits_of(fit_json);
  if (!fits.empty()) given.emplace_back("fit", kFitInMemory);
  Request request = request_of(read_keywords(table, given));
  request.fits = std::move(fits);
  return request;
}

// work(the table, or nullptr for a path) with the GIL released; a table's
// errors completed by the columns it left out (with_table_context).
template <class Work>
auto released(const TableHold* hold, Work&& work) {
  py::gil_scoped_release free;
  return hold != nullptr ? with_table_context(*hold, [&] { return work(&hold->table); }) : work(nullptr);
}

py::dict diagnose(const Keywords& keywords, const py::object& columns) {
  studies::DiagnoseRequest request =
      studies::diagnose_request(read_keywords(studies::diagnose_option_table(), for_record(keywords, columns)));
  const std::unique_ptr<TableHold> table = table_or_none(columns);
  const studies::DiagnoseRun run = released(table.get(), [&](const fit::Table* t) {
    return t != nullptr ? studies::run_diagnose(request, *t) : studies::run_diagnose(request);
  });
  return report(studies::diagnose_json(run).dump() + "\n", studies::diagnose_text(run));
}

py::dict allan(const Keywords& keywords, const py::object& columns, const py::object& fit_json) {
  const studies::AllanRequest request =
      with_fit(studies::allan_option_table(), &studies::allan_request, keywords, columns, fit_json);
  const std::unique_ptr<TableHold> table = table_or_none(columns);
  const std::vector<studies::AllanStudy> curves = released(table.get(), [&](const fit::Table* t) {
    return t != nullptr ? studies::run_allan(request, *t) : studies::run_allan(request);
  });
  return report(studies::allan_json(curves).dump() + "\n", studies::allan_text(curves));
}

py::dict compensate(const Keywords& keywords, const py::object& columns, const py::object& fit_json) {
  const studies::CompensateRequest request =
      with_fit(studies::compensate_option_table(), &studies::compensate_request, keywords, columns, fit_json);
  const std::unique_ptr<TableHold> table = table_or_none(columns);
  studies::CompensateRun run = released(table.get(), [&](const fit::Table* t) {
    return t != nullptr ? studies::run_compensate(request, *t) : studies::run_compensate(request);
  });
  py::dict out = report(studies::compensate_json(run).dump() + "\n", studies::compensate_text(run));
  // As the CSV of -o: time_s, temp_c, then per channel its output, model,
  // compensated output and outlier flag (prefixed by the channel's name when several).
  py::dict arrays;
  const bool several = run.channels.size() > 1;
  for (std::size_t k = 0; k < run.channels.size(); ++k) {
    fit::Compensation& c = run.channels[k];
    const std::string name = several ? run.fits[k].channel : std::string("gyro_dph");
    const std::string prefix = several ? name + "_" : std::string();
    std::vector<double> compensated(c.gyro_dph.size()), outlier(c.outlier.begin(), c.outlier.end());
    for (std::size_t i = 0; i < compensated.size(); ++i) compensated[i] = c.gyro_dph[i] - c.model_dph[i];
    if (k == 0) {
      arrays["time_s"] = owning_array(std::move(c.time_s));
      arrays["temp_c"] = owning_array(std::move(c.temp_c));
    }
    arrays[py::str(name)] = owning_array(std::move(c.gyro_dph));
    arrays[py::str(prefix + "model_dph")] = owning_array(std::move(c.model_dph));
    arrays[py::str(prefix + "compensated_dph")] = owning_array(std::move(compensated));
    arrays[py::str(prefix + "outlier")] = owning_array(std::move(outlier));
  }
  out["columns"] = arrays;
  return out;
}

py::dict check(const Keywords& keywords) {
  const studies::CheckRequest request = studies::check_request(read_keywords(studies::check_option_table(), keywords));
  const studies::CheckResult result = released(nullptr, [&](const fit::Table*) { return studies::run_check(request); });
  return report(studies::check_json(result).dump() + "\n", studies::check_text(result));
}

py::dict report_page(const Keywords& keywords) {
  const studies::ReportRequest request = studies::report_request(read_keywords(studies::report_option_table(), keywords));
  const studies::ReportRun run = released(nullptr, [&](const fit::Table*) { return studies::run_report(request); });
  py::dict out;
  out["html"] = run.html;
  out["twin"] = run.twin;
  out["html_file"] = run.html_file;
  out["twin_file"] = run.twin_file;
  out["text"] = run.text;
  return out;
}

py::dict export_fit(const Keywords& keywords, const py::object& columns) {
  studies::ExportRequest request = studies::export_request(read_keywords(studies::export_option_table(), keywords));
  const std::unique_ptr<TableHold> table = table_or_none(columns);
  if (table) request.data_table = &table->table;
  studies::ExportOutput output;
  {
    py::gil_scoped_release free;
    output = table ? with_table_context(*table, [&] { return studies::run_export(request); })
                   : studies::run_export(request);
  }
  py::dict out = report(studies::export_json(request, output).dump() + "\n", studies::export_text(output));
  out["warnings"] = output.warnings;
  return out;
}

py::dict plan(const Keywords& keywords) {
  const studies::plan::PlanRequest request = studies::plan_request(
      read_keywords(studies::plan_option_table(), keywords), std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml");
  studies::plan::PlanResult result;
  {
    py::gil_scoped_release free;
    result = studies::plan::run_plan(request);
  }
  return report(studies::plan::plan_json(result).dump() + "\n", studies::plan::plan_text(result));
}

}  // namespace

void add_studies(py::module_& m) {
  m.def("diagnose", &diagnose, py::arg("options"), py::arg("columns"));
  m.def("allan", &allan, py::arg("options"), py::arg("columns"), py::arg("fit"));
  m.def("compensate", &compensate, py::arg("options"), py::arg("columns"), py::arg("fit"));
  m.def("export", &export_fit, py::arg("options"), py::arg("columns"));
  m.def("check", &check, py::arg("options"));
  m.def("report", &report_page, py::arg("options"));
  m.def("plan", &plan, py::arg("options"));
  m.def("option_table", &option_rows, py::arg("command"));
}

}  // namespace gyrotherm::python
