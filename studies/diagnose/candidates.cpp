#include "studies/diagnose/candidates.h"

#include <fmt/format.h>

#include <algorithm>

#include "fit/data/column_role.h"
#include "fit/pipeline.h"
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

CandidateSet candidate_set(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                           const std::vector<std::string>& requested,
                           const std::vector<std::string>& excluded_columns) {
  CandidateSet set;
  std::vector<const fit::Term*> all;
  for (const fit::Term* term : fit::term_registry()) {
    if (contains(model, term)) continue;
    if (term->needs_temp2() && !data.has_temp2()) {
      set.skipped.push_back({.name = std::string(term->name), .reason = SkipReason::needs_temp2});
      continue;
    }
    all.push_back(term);
  }
  for (const auto& [name, values] : data.derived.extra) {
    if (std::find(excluded_columns.begin(), excluded_columns.end(), name) != excluded_columns.end() ||
        std::find(kNeverCandidates.begin(), kNeverCandidates.end(), name) != kNeverCandidates.end())
      continue;
    const fit::ColumnRole role = fit::column_role(name, values);
    if (role != fit::ColumnRole::cause && !named_in(requested, name)) {
      set.skipped.push_back({.name = name, .reason = SkipReason::column_role, .role = role});
      continue;
    }
    if (!fit::is_column_name(name)) {
      set.skipped.push_back({.name = name, .reason = SkipReason::unwritable_name});
      continue;
    }
    for (const bool rate : {false, true})
      if (const fit::Term* t = fit::column_term(name, rate); !contains(model, t)) all.push_back(t);
    set.columns.push_back(name);
  }
  set.steps = true;  // several steps are allowed: the family stays a candidate after one joins

  if (requested.empty()) {
    set.terms = std::move(all);
    return set;
  }
  // --candidates: exactly a list, or the default set with +/- changes.
  const bool changes = std::all_of(requested.begin(), requested.end(), [](const std::string& r) {
    return !r.empty() && (r[0] == '+' || r[0] == '-');
  });
  std::vector<const fit::Term*> chosen = changes ? all : std::vector<const fit::Term*>{};
  set.steps = changes;
  for (const std::string& r : requested) {
    const bool remove = changes && r[0] == '-';
    const std::string name = changes ? r.substr(1) : r;
    if (name == "step") {
      set.steps = !remove;
      continue;
    }
    const fit::Term* t = fit::term_by_name(name);
    if (t == nullptr)
      throw InputError(fmt::format("--candidates {}: unknown term '{}' (a known term, step, step@TIME "
                                   "or a column of the log)",
                                   r, name));
    if (remove) {
      std::erase(chosen, t);
    } else if (!contains(chosen, t) && !contains(model, t)) {
      if (fit::is_column_term(t) && !data.derived.extra.contains(t->column))
        throw InputError(fmt::format("--candidates {}: the log has no numeric column '{}'", r, t->column));
      chosen.push_back(t);
    }
  }
  set.terms = std::move(chosen);
  return set;
}

}  // namespace gyrotherm::studies
