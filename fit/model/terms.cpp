#include "fit/model/terms.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <deque>
#include <mutex>
#include <string>
#include <limits>
#include <span>

namespace gyrotherm::fit {
namespace {

// Every run-time term made so far, and the strings its views point into.
struct MadeTerms {
  std::mutex mutex;
  std::deque<Term> terms;
  std::deque<std::string> text;
  std::string_view keep(std::string s) { return text.emplace_back(std::move(s)); }
};

MadeTerms& made() {
  static MadeTerms m;
  return m;
}

}  // namespace

const std::vector<const Term*>& term_registry() {
  static const std::deque<Term> terms = [] {
    std::deque<Term> all;
    for (const effects::Effect* e : effects::registry()) {
      Term t;
      static_cast<effects::Effect&>(t) = *e;
      t.effect = e;
      all.push_back(t);
    }
    return all;
  }();
  static const std::vector<const Term*> pointers = [] {
    std::vector<const Term*> all;
    for (const Term& t : terms) all.push_back(&t);
    return all;
  }();
  return pointers;
}

const Term* find_term(std::string_view name) {
  for (const Term* t : term_registry())
    if (t->name == name) return t;
  return nullptr;
}

void Term::compute(const DerivedSeries& s, double theta, std::span<double> out) const {
  if (effect != nullptr) {
    effect->compute(s, theta, out);
  } else if (family == effects::Family::step) {
    for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.time_s[p] >= step_time_s ? 1.0 : 0.0;
  } else {
    const auto& source = column_rate ? s.extra_rate : s.extra;
    const auto it = source.find(column);
    for (std::size_t p = 0; p < out.size(); ++p)
      out[p] = it == source.end() ? std::numeric_limits<double>::quiet_NaN() : it->second[p];
  }
}

bool is_column_name(std::string_view name) {
  if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
  });
}

namespace {

// The term called `name`, made by fill(term, keep) on first use (keep stores a
// string for the term's views).
template <class Fill>
const Term* made_term(const std::string& name, Fill fill) {
  MadeTerms& m = made();
  const std::lock_guard lock(m.mutex);
  for (const Term& t : m.terms)
    if (t.name == name) return &t;
  Term t;
  t.name = m.keep(name);
  fill(t, [&m](std::string text) { return m.keep(std::move(text)); });
  return &m.terms.emplace_back(t);
}

}  // namespace

const Term* step_term(double time_s) {
  return made_term(fmt::format("step@{:g}", time_s), [&](Term& t, auto keep) {
    t.meaning = keep(fmt::format("a bias step at {:g} s (a mode hop, a shock, a reset)", time_s));
    t.unit = "1";
    t.columns = effects::kTime;
    t.family = effects::Family::step;
    t.c_form.expression = keep(fmt::format("(rel >= {:.17g} ? 1.0 : 0.0)", time_s));
    t.step_time_s = time_s;
  });
}

const Term* column_term(std::string_view column, bool rate) {
  return made_term(rate ? fmt::format("d({})", column) : std::string(column), [&](Term& t, auto keep) {
    t.family = rate ? effects::Family::rate : effects::Family::logged;  // no C form: the C interface has no such input
    t.column = keep(std::string(column));
    t.column_rate = rate;
    t.meaning = keep(rate ? fmt::format("the rate of the logged column {}", column)
                          : fmt::format("the logged column {}", column));
    t.unit = keep(rate ? fmt::format("{} unit/s", column) : fmt::format("{} unit", column));
    t.columns = effects::kTime;
  });
}

const Term* term_by_name(std::string_view name) {
  if (const Term* t = find_term(name)) return t;
  if (name.starts_with("step@")) {
    const std::string_view number = name.substr(5);
    double time_s = 0.0;
    const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), time_s);
    if (ec != std::errc() || ptr != number.data() + number.size() || !std::isfinite(time_s) || time_s < 0.0)
      return nullptr;
    return step_term(time_s);
  }
  if (name.starts_with("d(") && name.ends_with(")") && is_column_name(name.substr(2, name.size() - 3)))
    return column_term(name.substr(2, name.size() - 3), true);
  if (is_column_name(name)) return column_term(name, false);
  return nullptr;
}

Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters) {
  const auto l = static_cast<Eigen::Index>(derived.size());
  Eigen::MatrixXd x(l, static_cast<Eigen::Index>(terms.size()));
  for (std::size_t j = 0; j < terms.size(); ++j)
    terms[j]->compute(derived, parameters[j],
                        std::span<double>(x.col(static_cast<Eigen::Index>(j)).data(),
                                          static_cast<std::size_t>(l)));
  return x;
}

Eigen::MatrixXd design_matrix_held(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                                   const std::vector<double>& parameters, double lo_c, double hi_c) {
  Eigen::MatrixXd x = design_matrix(derived, terms, parameters);
  if (std::all_of(derived.temp_c.begin(), derived.temp_c.end(), [&](double t) { return t >= lo_c && t <= hi_c; }))
    return x;
  const DerivedSeries held = held_within(derived, lo_c, hi_c);
  for (std::size_t j = 0; j < terms.size(); ++j) {
    if (!reads_temperature_level(terms[j])) continue;
    terms[j]->compute(held, parameters[j],
                      std::span<double>(x.col(static_cast<Eigen::Index>(j)).data(), static_cast<std::size_t>(x.rows())));
  }
  return x;
}

DerivedSeries held_within(const DerivedSeries& derived, double lo_c, double hi_c) {
  DerivedSeries held = derived;
  for (double& t : held.temp_c) t = std::clamp(t, lo_c, hi_c);
  return held;
}

std::vector<double> default_parameters(const std::vector<const Term*>& terms) {
  std::vector<double> p(terms.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t j = 0; j < terms.size(); ++j)
    if (terms[j]->parameter) p[j] = std::sqrt(terms[j]->parameter->lower * terms[j]->parameter->upper);
  return p;
}

}  // namespace gyrotherm::fit
