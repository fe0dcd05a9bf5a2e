#pragma once
// An effect end to end through the command line, as a user meets it: simulated
// as a hidden effect, fitted, diagnosed, compensated with and exported. Each
// effect's own test (tests/NAME_test.cpp) calls it with a truth the record can
// show; the C export of every registry effect is checked sample by sample in
// tests/c_export_test.cpp.

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "fit/model/terms.h"

namespace gyrotherm::testing {

struct RoundTrip {
  std::string scenario;      // shipped scenario, e.g. "cycle"
  std::string term;          // the effect's name
  double coefficient = 0.0;  // its hidden coefficient
  double tolerance = 0.2;    // the fitted coefficient within this share of the truth
};

// The effect's regressor where the temperature is temp_c (at 0, 100, 200, … s,
// no rate): exactly `expected`.
inline void expect_regressor_at(const std::string& term, const std::vector<double>& temp_c,
                                const std::vector<double>& expected) {
  const fit::Term* t = fit::find_term(term);
  ASSERT_NE(t, nullptr) << term;
  fit::DerivedSeries s;
  for (std::size_t k = 0; k < temp_c.size(); ++k) s.time_s.push_back(100.0 * static_cast<double>(k));
  s.temp_c = temp_c;
  s.rate_c_per_s.assign(temp_c.size(), 0.0);
  s.accel_c_per_s2.assign(temp_c.size(), 0.0);
  std::vector<double> r(temp_c.size());
  t->compute(s, 0.0, r);
  EXPECT_EQ(r, expected) << term;
}

inline void expect_round_trip(const RoundTrip& r) {
  SCOPED_TRACE(r.scenario + ", hidden " + r.term);
  const fit::Term* term = fit::find_term(r.term);
  ASSERT_NE(term, nullptr);
  ScratchDir dir;
  const std::string hidden = fmt::format("'{}={:.17g}'", r.term, r.coefficient);

  // 1. simulate --hidden: the truth beside the record names it.
  simulate_shipped(dir, r.scenario, "--hidden " + hidden, "h.csv");
  const auto truth = nlohmann::json::parse(slurp(dir / "h.truth.json"));
  EXPECT_EQ(truth["coefficients"][r.term].get<double>(), r.coefficient);

  // 2. fit --add: the coefficient is recovered, its 95 % interval covers the
  //    truth, and the model is better than without it.
  const auto without = run_cli(dir, "fit h.csv --json");
  const auto with = run_cli(dir, "fit h.csv --add '" + r.term + "' --json -o fit.json");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  const auto f = nlohmann::json::parse(with.out);
  const double estimate = f["coefficients"][r.term].get<double>();
  EXPECT_NEAR(estimate / r.coefficient, 1.0, r.tolerance) << estimate;
  const auto interval = f["intervals_95"][r.term];
  EXPECT_LE(interval[0].get<double>(), r.coefficient);
  EXPECT_GE(interval[1].get<double>(), r.coefficient);
  EXPECT_LT(f["instability_after_dph"].get<double>(),
            nlohmann::json::parse(without.out)["instability_after_dph"].get<double>());

  // 3. diagnose: the paper's model misses it, and the first candidate, which
  //    removes most of the excess, is the effect, or one the diagnosis says
  //    this record cannot tell it from.
  const auto diagnosis = run_cli(dir, "diagnose h.csv --json");
  ASSERT_EQ(diagnosis.exit_code, 0) << diagnosis.err;
  const auto d = nlohmann::json::parse(diagnosis.out);
  ASSERT_FALSE(d["missing_effects"].empty());
  const auto& best = d["missing_effects"][0];
  bool named = best["term"] == r.term;
  for (const auto& other : best["confounded_with"]) named |= other == r.term;
  EXPECT_TRUE(named) << d["verdict"];
  EXPECT_GE(best["reduction_pct"].get<double>(), 80.0);
  // Significant alone, or (confounded) as a group; never alone when grouped.
  const bool grouped = !best["confounded_with"].empty();
  EXPECT_TRUE(grouped ? best["group_significant"].get<bool>() : best["significant"].get<bool>())
      << d["verdict"];
  if (grouped) {
    EXPECT_FALSE(best["significant"].get<bool>()) << best;
  }

  // 4. compensate --causal with the fit: the instability falls.
  const auto compensated = run_cli(dir, "compensate h.csv --fit fit.json --causal --json -o c.csv");
  ASSERT_EQ(compensated.exit_code, 0) << compensated.err;
  const auto c = nlohmann::json::parse(compensated.out);
  EXPECT_GT(c["ratio"].get<double>(), 3.0);

  // 5. export: C writes any term; the autopilots hold powers of T up to 3 and
  //    refuse the rest by name, writing nothing.
  EXPECT_EQ(run_cli(dir, "export fit.json --format c -o c.h").exit_code, 0);
  for (const char* format : {"px4", "ardupilot"}) {
    const auto exported = run_cli(dir, std::string("export fit.json --format ") + format + " -o " + format + ".txt");
    const bool expressible = term->temperature_power >= 1 && term->temperature_power <= 3;
    EXPECT_EQ(exported.exit_code, expressible ? 0 : 2) << format << ": " << exported.err;
    if (!expressible) {
      EXPECT_NE(exported.err.find("cannot express"), std::string::npos) << exported.err;
      EXPECT_NE(exported.err.find(r.term), std::string::npos) << exported.err;
      EXPECT_FALSE(std::filesystem::exists(dir / (std::string(format) + ".txt")));
    }
  }
}

}  // namespace gyrotherm::testing
