#pragma once
// Model formulas: term names joined by '+', e.g. "T + T^2 + dT" (the
// paper's eq. 6, the default): the registry's, step@TIME, and the log's own
// columns NAME and d(NAME) (fit/model/terms.h). The intercept is always in;
// writing "1" is allowed and changes nothing. Spaces are ignored.

#include <string>
#include <string_view>
#include <vector>

#include "fit/model/terms.h"

namespace gyrotherm::fit {

inline constexpr std::string_view kDefaultModel = "T + T^2 + dT";

// Throws InputError for an empty formula, an unknown term (listing the known
// ones) or a term given twice.
std::vector<const Term*> parse_formula(std::string_view formula);
// The canonical text of a term list: "T + T^2 + dT".
std::string formula_text(const std::vector<const Term*>& terms);
// The names of a term list, in order.
std::vector<std::string> term_names(const std::vector<const Term*>& terms);

}  // namespace gyrotherm::fit
