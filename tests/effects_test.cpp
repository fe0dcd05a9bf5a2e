// The effect registry (sim/effects/): each regressor against values computed
// by hand on a small state series, and the contract every registered effect
// keeps (tests loop over the registry, so a new effect is checked too).

#include "sim/effects/effect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace gyrotherm::effects {
namespace {

// Four points of a made-up state: heating, in the dead band, cooling.
EffectSeries small_state() {
  EffectSeries s;
  s.time_s = {0.0, 600.0, 1200.0, 1800.0};
  s.temp_c = {20.0, 21.0, 22.0, 21.5};
  s.rate_c_per_s = {2e-3, 1e-3, 5e-5, -1e-3};
  s.accel_c_per_s2 = {0.0, -1e-6, -2e-6, 1e-6};
  s.temp2_c = {20.5, 21.25, 22.5, 21.0};
  s.switch_on_s = 0.0;
  return s;
}

std::vector<double> values(const char* name, double parameter = 0.0) {
  const Effect* e = find(name);
  EXPECT_NE(e, nullptr) << name;
  return e ? regressor_values(*e, small_state(), parameter) : std::vector<double>{};
}

TEST(Effects, RegressorsByHand) {
  const EffectSeries s = small_state();
  EXPECT_EQ(values("T")[1], 21.0);
  EXPECT_EQ(values("T^2")[2], 22.0 * 22.0);
  EXPECT_NEAR(values("T^3")[3], std::pow(21.5, 3), 1e-12);
  EXPECT_EQ(values("dT")[3], -1e-3);
  EXPECT_NEAR(values("T*dT")[0], 20.0 * 2e-3, 1e-15);
  EXPECT_EQ(values("d2T")[2], -2e-6);
  EXPECT_NEAR(values("grad")[3], 21.0 - 21.5, 1e-15);
  EXPECT_NEAR(values("warmup", 1800.0)[1], std::exp(-600.0 / 1800.0), 1e-15);
  EXPECT_NEAR(values("t")[3], 0.5, 1e-15);
  // hyst: +1 heating, 0 inside the dead band, −1 cooling.
  const std::vector<double> h = values("hyst", 2e-4);
  EXPECT_EQ(h[0], 1.0);
  EXPECT_EQ(h[2], 0.0);
  EXPECT_EQ(h[3], -1.0);
  EXPECT_EQ(values("hyst", 5e-3)[0], 0.0);
}

TEST(Effects, WarmupStartsAtSwitchOnAndIsGoneForAGyroRunningBefore) {
  EffectSeries s = small_state();
  const Effect& warmup = *find("warmup");
  s.switch_on_s = -600.0;
  EXPECT_NEAR(regressor_values(warmup, s, 1200.0)[0], std::exp(-0.5), 1e-15);
  s.switch_on_s = -std::numeric_limits<double>::infinity();
  for (double r : regressor_values(warmup, s, 1200.0)) EXPECT_EQ(r, 0.0);
}

TEST(Effects, ContractTermNamesAreRegistered) {
  // The public contract (docs/contracts.md): these names exist and keep their meaning.
  for (const char* name : {"T", "T^2", "T^3", "dT", "T*dT", "d2T", "grad", "hyst", "warmup", "t"})
    EXPECT_NE(find(name), nullptr) << name;
  EXPECT_EQ(find("bogus"), nullptr);
  // The paper's three terms are the [truth] ones.
  EXPECT_EQ(find_by_truth_key("b1_dph_per_c"), find("T"));
  EXPECT_EQ(find_by_truth_key("b2_dph_per_c2"), find("T^2"));
  EXPECT_EQ(find_by_truth_key("b3_dph_per_c_per_s"), find("dT"));
  EXPECT_EQ(find_by_truth_key(""), nullptr);
}

TEST(Effects, EveryEffectKeepsTheContract) {
  std::set<std::string> seen_names, seen_keys;
  const EffectSeries s = small_state();
  for (const Effect* e : registry()) {
    SCOPED_TRACE(std::string(e->name));
    EXPECT_FALSE(e->name.empty());
    EXPECT_TRUE(seen_names.insert(std::string(e->name)).second) << "a name used twice";
    EXPECT_EQ(e->name.find_first_of(" +"), std::string_view::npos) << "a formula could not name it";
    EXPECT_FALSE(e->meaning.empty());
    EXPECT_FALSE(e->unit.empty());
    EXPECT_NE(e->regressor, nullptr);
    EXPECT_NE(e->columns, 0u);
    EXPECT_EQ(e->hidden(), e->truth_key.empty());
    EXPECT_EQ(e->coefficient_unit().rfind("°/h", 0), 0u);
    EXPECT_FALSE(e->column_names().empty());
    // Its family: a registry effect is one of the physical ones, not a term
    // the fit makes.
    EXPECT_NE(e->family, Family::step);
    EXPECT_NE(e->family, Family::logged);
    // Its C form: an expression, and for a filter its first value too; a
    // parameter is written into it ({theta}) exactly when there is one.
    EXPECT_FALSE(e->c_form.expression.empty()) << "no C form: export --format c cannot write it";
    const bool uses_theta = e->c_form.expression.find("{theta}") != std::string_view::npos ||
                            e->c_form.initial.find("{theta}") != std::string_view::npos;
    EXPECT_EQ(uses_theta, e->parameter.has_value()) << e->c_form.expression;
    EXPECT_EQ(e->c_form.stateful(), e->family == Family::temperature_state);
    // A filter has its recursion, and the regressor is that recursion point
    // by point (the real-time compensator carries it from window to window).
    EXPECT_EQ(e->next != nullptr, e->c_form.stateful());
    if (e->next) {
      const double theta = e->parameter ? e->parameter->simulator_default : 0.0;
      const std::vector<double> r = regressor_values(*e, s, theta);
      for (std::size_t k = 1; k < s.size(); ++k) EXPECT_EQ(e->next(s, k, theta, r[k - 1]), r[k]) << k;
    }
    // A rate vanishes in a soak; an effect of another family does not, or not
    // everywhere (diagnosis reads "a rate" as zero where the temperature holds).
    EffectSeries soak = s;
    std::fill(soak.rate_c_per_s.begin(), soak.rate_c_per_s.end(), 0.0);
    std::fill(soak.accel_c_per_s2.begin(), soak.accel_c_per_s2.end(), 0.0);
    std::fill(soak.temp_c.begin(), soak.temp_c.end(), 20.0);
    const std::vector<double> in_soak = regressor_values(*e, soak, e->parameter ? e->parameter->lower : 0.0);
    const bool all_zero = std::all_of(in_soak.begin(), in_soak.end(), [](double r) { return r == 0.0; });
    if (e->family == Family::rate) {
      EXPECT_TRUE(all_zero);
    }
    if (e->family == Family::temperature_power || e->family == Family::temperature_state ||
        e->family == Family::time) {
      EXPECT_FALSE(all_zero);
    }
    // Its power of T, exactly for the powers of T, and the regressor is that power.
    EXPECT_EQ(e->temperature_power > 0, e->family == Family::temperature_power);
    if (e->temperature_power > 0) {
      const std::vector<double> r = regressor_values(*e, s, 0.0);
      for (std::size_t p = 0; p < s.size(); ++p)
        EXPECT_NEAR(r[p], std::pow(s.temp_c[p], e->temperature_power), 1e-12 * std::abs(r[p])) << p;
    }
    if (e->parameter) {
      const EffectParameter& p = *e->parameter;
      EXPECT_FALSE(p.name.empty());
      EXPECT_TRUE(seen_keys.insert(std::string(p.gyro_key)).second) << "a gyro key used twice";
      EXPECT_GT(p.lower, 0.0) << "searched on a log scale";
      EXPECT_LT(p.lower, p.upper);
      EXPECT_TRUE(p.simulator_default > 0.0 || p.may_be_zero);
    }
    // Finite regressors on an ordinary state, at the parameter's bounds too.
    for (double parameter : e->parameter ? std::vector<double>{e->parameter->lower, e->parameter->upper}
                                         : std::vector<double>{0.0})
      for (double r : regressor_values(*e, s, parameter)) EXPECT_TRUE(std::isfinite(r));
    // An effect that does not read temp2_c works without it.
    if (!e->needs_temp2()) {
      EffectSeries without = s;
      without.temp2_c.clear();
      EXPECT_EQ(regressor_values(*e, without, e->parameter ? e->parameter->lower : 0.0).size(), s.size());
    }
  }
  EXPECT_EQ(names().find(std::string(registry().front()->name)), 0u);
  for (const Effect* e : registry())
    EXPECT_EQ(hidden_names().find(std::string(e->name)) != std::string::npos || !e->hidden(), true);
}

}  // namespace
}  // namespace gyrotherm::effects
