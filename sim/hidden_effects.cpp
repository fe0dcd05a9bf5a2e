#include "sim/hidden_effects.h"

namespace gyrotherm::sim {

bool is_hidden_term(std::string_view name) {
  for (const HiddenTerm& term : kHiddenTerms)
    if (term.name == name) return true;
  return false;
}

std::string hidden_term_list() {
  std::string out;
  for (const HiddenTerm& term : kHiddenTerms) {
    if (!out.empty()) out += ", ";
    out += term.name;
  }
  return out;
}

}  // namespace gyrotherm::sim
