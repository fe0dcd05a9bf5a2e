#include "fit/model/formula.h"

#include <fmt/format.h>

#include <algorithm>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

std::vector<const Term*> parse_formula(std::string_view formula) {
  std::vector<const Term*> terms;
  std::string cleaned;
  for (char c : formula)
    if (c != ' ' && c != '\t') cleaned.push_back(c);
  if (cleaned.empty())
    throw InputError(fmt::format("model formula is empty; write terms joined by '+', e.g. '{}' "
                                 "(known terms: {})",
                                 kDefaultModel, term_list()));
  std::size_t start = 0;
  while (start <= cleaned.size()) {
    const std::size_t plus = std::min(cleaned.find('+', start), cleaned.size());
    const std::string name = cleaned.substr(start, plus - start);
    start = plus + 1;
    if (name.empty())
      throw InputError(fmt::format("model '{}': an empty term (two '+' in a row, or one at an "
                                   "end)",
                                   formula));
    if (name == "1") continue;
    const Term* term = term_by_name(name);
    if (term == nullptr)
      throw InputError(fmt::format("model '{}': unknown term '{}' (known terms: {}), nor step@TIME "
                                   "nor a column of the log by its name",
                                   formula, name, term_list()));
    if (std::find(terms.begin(), terms.end(), term) != terms.end())
      throw InputError(fmt::format("model '{}': term '{}' appears twice", formula, name));
    terms.push_back(term);
  }
  if (terms.empty())
    throw InputError(fmt::format("model '{}' has no terms besides the intercept", formula));
  return terms;
}

std::string formula_text(const std::vector<const Term*>& terms) {
  std::string out;
  for (const Term* t : terms) out += (out.empty() ? "" : " + ") + std::string(t->name);
  return out;
}

std::vector<std::string> term_names(const std::vector<const Term*>& terms) {
  std::vector<std::string> names;
  for (const Term* t : terms) names.emplace_back(t->name);
  return names;
}

}  // namespace gyrotherm::fit
