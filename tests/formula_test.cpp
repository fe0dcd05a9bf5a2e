// Model formulas: parsing, canonical text, and the errors a user sees.

#include "fit/model/formula.h"

#include <gtest/gtest.h>

#include <string>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

TEST(Formula, ParsesTheDefaultAndRejectsBadFormulas) {
  const auto terms = parse_formula(" T+T^2 + dT ");
  ASSERT_EQ(terms.size(), 3u);
  EXPECT_EQ(formula_text(terms), "T + T^2 + dT");
  EXPECT_EQ(term_names(terms), (std::vector<std::string>{"T", "T^2", "dT"}));
  EXPECT_EQ(formula_text(parse_formula("1 + grad")), "grad");
  auto message = [](const char* f) {
    try {
      parse_formula(f);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("T + T^7").find("unknown term 'T^7' (known terms: " + term_list() + ")"),
            std::string::npos);
  EXPECT_NE(message("T + T").find("'T' appears twice"), std::string::npos);
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message("T ++ dT").find("empty term"), std::string::npos);
  EXPECT_NE(message("1").find("no terms"), std::string::npos);
}

TEST(Formula, EveryRegisteredTermCanBeWritten) {
  for (const Term* t : term_registry()) {
    const auto parsed = parse_formula(std::string(t->name));
    ASSERT_EQ(parsed.size(), 1u) << t->name;
    EXPECT_EQ(parsed[0], t);
  }
}

}  // namespace
}  // namespace gyrotherm::fit
