#include "studies/diagnose/candidates.h"

#include "fit/pipeline.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include <fmt/ranges.h>

#include "fit/data/header_units.h"

#include "sim/util/input_error.h"

namespace gyrotherm::studies {
namespace {

bool contains(const std::vector<const fit::Term*>& v, const fit::Term* t) {
  return std::find(v.begin(), v.end(), t) != v.end();
}

bool named_in(const std::vector<std::string>& requested, const std::string& column) {
  return std::any_of(requested.begin(), requested.end(), [&](const std::string& r) {
    const std::string_view name = !r.empty() && (r[0] == '+' || r[0] == '-') ? std::string_view(r).substr(1) : r;
    return name == column || name == "d(" + column + ")";
  });
}

}  // namespace

bool sensor_channel(const std::string& column) {
  if (fit::unit_in_header(fit::Quantity::gyro, column).unit != nullptr) return true;
  std::string first;  // the name's first word, lower case
  for (const char c : column) {
    if (!std::isalnum(static_cast<unsigned char>(c))) break;
    first += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  for (const std::string_view stem : {"gyr", "acc", "mag", "omega"})
    if (first.starts_with(stem)) return true;
  for (const std::string_view kind : {"gyro", "acc", "mag"})
    if (first.size() > 1 && (first[0] == 'x' || first[0] == 'y' || first[0] == 'z') && first.substr(1).starts_with(kind))
      return true;
  // g, a, m or w, an optional digit, then the axis (and an optional digit).
  const auto axis = [](char c) { return c == 'x' || c == 'y' || c == 'z'; };
  std::size_t k = 0;
  if (first.empty() || std::string_view("gamw").find(first[0]) == std::string_view::npos) return false;
  k = 1;
  if (k < first.size() && std::isdigit(static_cast<unsigned char>(first[k]))) ++k;
  if (k >= first.size() || !axis(first[k])) return false;
  ++k;
  if (k < first.size() && std::isdigit(static_cast<unsigned char>(first[k]))) ++k;
  return k == first.size();
}

CandidateSet candidate_set(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                           const std::vector<double>& parameters,
                           const std::vector<std::string>& requested,
                           const std::vector<std::string>& excluded_columns, std::uint64_t seed) {
  CandidateSet set;
  std::vector<const fit::Term*> all;
  for (const fit::Term* term : fit::term_registry()) {
    if (contains(model, term)) continue;
    if (term->needs_temp2() && !data.has_temp2()) {
      set.skipped.push_back(std::string(term->name) + " (needs temp2_c)");
      continue;
    }
    all.push_back(term);
  }
  std::vector<std::string> sensors;
  for (const auto& [name, values] : data.derived.extra) {
    if (std::find(excluded_columns.begin(), excluded_columns.end(), name) != excluded_columns.end() ||
        std::find(kNeverCandidates.begin(), kNeverCandidates.end(), name) != kNeverCandidates.end())
      continue;
    if (sensor_channel(name) && !named_in(requested, name)) {
      sensors.push_back(name);
      continue;
    }
    if (!fit::is_column_name(name)) {
      set.skipped.push_back(fmt::format("column '{}' (its name cannot be written in a model: use "
                                        "letters, digits, '_' and '.')",
                                        name));
      continue;
    }
    for (const bool rate : {false, true})
      if (const fit::Term* t = fit::column_term(name, rate); !contains(model, t)) all.push_back(t);
    set.columns.push_back(name);
  }
  if (!sensors.empty())
    set.skipped.push_back(fmt::format("column{} {} (another motion sensor's channel{}, not a cause of the "
                                      "bias; name one in --candidates +NAME to try it)",
                                      sensors.size() == 1 ? "" : "s", fmt::join(sensors, ", "),
                                      sensors.size() == 1 ? "" : "s"));
  // Steps in the model's residual that its noise does not explain.
  std::vector<double> since_start(data.series.size());
  for (std::size_t p = 0; p < since_start.size(); ++p)
    since_start[p] = data.series.time_s[p] - data.series.start_time_s;
  const Eigen::MatrixXd design = fit::design_matrix(data.derived, model, parameters);
  StepSearch search;
  search.seed = seed;
  const fit::WindowGrid grid = fit::window_grid(data);
  if (grid.window_s > 0.0) search.grid = &grid;
  set.steps = find_steps(since_start, design,
                         Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                                           static_cast<Eigen::Index>(data.series.size())),
                         search);
  std::vector<const fit::Term*> steps;
  for (const StepCandidate& s : set.steps)
    if (const fit::Term* t = fit::step_term(s.time_s); !contains(model, t)) steps.push_back(t);
  all.insert(all.end(), steps.begin(), steps.end());

  if (requested.empty()) {
    set.terms = std::move(all);
    return set;
  }
  // --candidates: exactly a list, or the default set with +/- changes.
  const bool changes = std::all_of(requested.begin(), requested.end(), [](const std::string& r) {
    return !r.empty() && (r[0] == '+' || r[0] == '-');
  });
  std::vector<const fit::Term*> chosen = changes ? all : std::vector<const fit::Term*>{};
  for (const std::string& r : requested) {
    const bool remove = changes && r[0] == '-';
    const std::string name = changes ? r.substr(1) : r;
    std::vector<const fit::Term*> named;
    if (name == "step") {
      named = steps;
    } else if (const fit::Term* t = fit::term_by_name(name)) {
      named = {t};
    } else {
      throw InputError(fmt::format("--candidates {}: unknown term '{}' (a known term, step, step@TIME "
                                   "or a column of the log)",
                                   r, name));
    }
    for (const fit::Term* t : named) {
      if (remove) {
        std::erase(chosen, t);
      } else if (!contains(chosen, t) && !contains(model, t)) {
        if (fit::is_column_term(t) && !data.derived.extra.contains(t->column))
          throw InputError(fmt::format("--candidates {}: the log has no numeric column '{}'", r, t->column));
        chosen.push_back(t);
      }
    }
  }
  set.terms = std::move(chosen);
  return set;
}

}  // namespace gyrotherm::studies
