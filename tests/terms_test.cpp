// fit/model/terms: the registry's effects as terms, and the fit's own terms
// (step@TIME, a log column NAME, its rate d(NAME)) with their families, C
// forms and regressors on a small derived series.

#include "fit/model/terms.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gyrotherm::fit {
namespace {

// Four windows 100 s apart, warming at 0.01 °C/s, with a logged supply voltage.
DerivedSeries small_series() {
  DerivedSeries s;
  for (int k = 0; k < 4; ++k) {
    s.time_s.push_back(100.0 * k);
    s.temp_c.push_back(20.0 + k);
  }
  s.rate_c_per_s.assign(4, 0.01);
  s.accel_c_per_s2.assign(4, 0.0);
  s.extra = {{"supply_v", {28.0, 28.5, 27.5, 28.0}}};
  s.extra_rate = {{"supply_v", {0.005, -0.0025, -0.0025, 0.005}}};
  return s;
}

std::vector<double> values(const Term& t, const DerivedSeries& s) {
  std::vector<double> r(s.size());
  t.compute(s, 0.0, r);
  return r;
}

TEST(Terms, EveryRegistryEffectIsATermThatComputesAsTheEffect) {
  ASSERT_EQ(term_registry().size(), effects::registry().size());
  const DerivedSeries s = small_series();
  for (std::size_t k = 0; k < term_registry().size(); ++k) {
    const Term& t = *term_registry()[k];
    SCOPED_TRACE(std::string(t.name));
    EXPECT_EQ(t.effect, effects::registry()[k]);
    EXPECT_EQ(find_term(t.name), &t);
    EXPECT_EQ(t.family, t.effect->family);
    EXPECT_EQ(t.c_form.expression, t.effect->c_form.expression);
    if (t.needs_temp2()) continue;
    const double theta = t.parameter ? t.parameter->lower : 0.0;
    std::vector<double> as_term(s.size());
    t.compute(s, theta, as_term);
    EXPECT_EQ(as_term, effects::regressor_values(*t.effect, s, theta));
  }
  EXPECT_EQ(find_term("supply_v"), nullptr) << "a column is no registry term";
}

TEST(Terms, AStepIsZeroBeforeItsTimeAndOneFrom) {
  const Term* step = term_by_name("step@200");
  ASSERT_NE(step, nullptr);
  EXPECT_EQ(step, step_term(200.0)) << "one term per name";
  EXPECT_TRUE(is_step_term(step));
  EXPECT_FALSE(is_column_term(step));
  EXPECT_EQ(step->family, effects::Family::step);
  EXPECT_EQ(step->effect, nullptr);
  EXPECT_EQ(step->c_form.expression, "(rel >= 200 ? 1.0 : 0.0)");
  EXPECT_EQ(values(*step, small_series()), (std::vector<double>{0.0, 0.0, 1.0, 1.0}));
  EXPECT_EQ(term_by_name("step@-5"), nullptr);
  EXPECT_EQ(term_by_name("step@x"), nullptr);
}

TEST(Terms, ALogColumnAndItsRate) {
  const Term* v = term_by_name("supply_v");
  const Term* dv = term_by_name("d(supply_v)");
  ASSERT_NE(v, nullptr);
  ASSERT_NE(dv, nullptr);
  EXPECT_TRUE(is_column_term(v));
  EXPECT_EQ(v->column, "supply_v");
  EXPECT_EQ(v->family, effects::Family::logged);
  EXPECT_EQ(dv->family, effects::Family::rate) << "a rate: diagnosis treats it as one";
  EXPECT_TRUE(v->c_form.expression.empty()) << "the C interface has no such input";
  const DerivedSeries s = small_series();
  EXPECT_EQ(values(*v, s), s.extra.at("supply_v"));
  EXPECT_EQ(values(*dv, s), s.extra_rate.at("supply_v"));
  // A column the series lacks gives NaN (check_columns refuses it before a fit).
  for (double r : values(*term_by_name("missing_col"), s)) EXPECT_TRUE(std::isnan(r));
  EXPECT_EQ(term_by_name("2bad"), nullptr);
}

}  // namespace
}  // namespace gyrotherm::fit
