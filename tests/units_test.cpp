// The unit table (fit/data/units.cpp): every entry complete, each converts a
// known value exactly as physics says, and every unit is accepted by the
// reader (a column in that unit gives the same record as one in the base
// unit).

#include "fit/data/units.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <set>

#include "expect_input_error.h"
#include "fit/data/measurement.h"
#include "cli_runner.h"
#include <nlohmann/json.hpp>

namespace gyrotherm::fit {
namespace {

using testing::expect_input_error;
using testing::ScratchDir;
using testing::write_text;

TEST(Units, EveryEntryIsComplete) {
  for (const Quantity q : {Quantity::time, Quantity::gyro, Quantity::temperature}) {
    std::set<std::string_view> names;
    int bases = 0;
    for (const Unit& u : unit_table()) {
      if (u.quantity != q) continue;
      SCOPED_TRACE(std::string(u.name));
      EXPECT_FALSE(u.name.empty());
      EXPECT_TRUE(names.insert(u.name).second) << "a name used twice";
      EXPECT_FALSE(u.meaning.empty());
      EXPECT_TRUE(std::isfinite(u.to_base(1.0)));
      EXPECT_TRUE(u.affine != nullptr || u.factor > 0.0);
      bases += u.is_base();
      EXPECT_EQ(&find_unit(q, u.name, "--x"), &u);
    }
    EXPECT_EQ(bases, 1) << "one base unit per quantity";
    EXPECT_TRUE(find_unit(q, base_unit(q), "--x").is_base());
    EXPECT_EQ(unit_names(q).find(base_unit(q)), 0u) << "the base unit is listed first";
  }
}

double in_base(Quantity q, std::string_view name, double value) { return find_unit(q, name, "--x").to_base(value); }

TEST(Units, ConvertKnownValues) {
  EXPECT_EQ(in_base(Quantity::time, "s", 2.5), 2.5);
  EXPECT_DOUBLE_EQ(in_base(Quantity::time, "ms", 1500.0), 1.5);
  EXPECT_DOUBLE_EQ(in_base(Quantity::time, "us", 2e6), 2.0);
  EXPECT_EQ(in_base(Quantity::gyro, "dph", 7.0), 7.0);
  EXPECT_DOUBLE_EQ(in_base(Quantity::gyro, "dps", 1.0), 3600.0);
  EXPECT_DOUBLE_EQ(in_base(Quantity::gyro, "mdps", 1.0), 3.6);
  EXPECT_NEAR(in_base(Quantity::gyro, "rad/s", 1.0), 3600.0 * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_EQ(in_base(Quantity::temperature, "C", -5.0), -5.0);
  EXPECT_DOUBLE_EQ(in_base(Quantity::temperature, "K", 273.15), 0.0);
  EXPECT_DOUBLE_EQ(in_base(Quantity::temperature, "F", 212.0), 100.0);
  EXPECT_DOUBLE_EQ(in_base(Quantity::temperature, "F", -40.0), -40.0);
}

TEST(Units, AnUnknownNameIsRefusedWithTheKnownOnes) {
  expect_input_error([] { find_unit(Quantity::gyro, "furlong/s", "--gyro-unit"); },
                     {"--gyro-unit furlong/s: unknown unit (expected one of " + unit_names(Quantity::gyro) + ")"});
  EXPECT_EQ(unit_names(Quantity::time, " or "), "s, ms, us, ns, min or h");
}

// A gyro column written in each unit reads as the record in °/h.
TEST(Units, EveryGyroUnitReadsAsDegreesPerHour) {
  ScratchDir dir;
  for (const Unit& u : unit_table()) {
    if (u.quantity != Quantity::gyro) continue;
    SCOPED_TRACE(std::string(u.name));
    const double per_unit = u.to_base(1.0);
    std::string text = "time_s,temp_c,gyro\n";  // a header that states no unit: the option's
    for (int k = 0; k < 5; ++k) text += fmt::format("{},20,{:.17g}\n", k, (7.0 + 0.01 * k) / per_unit);
    write_text(dir / "g.csv", text);
    ColumnMap columns;
    columns.gyro = "gyro";
    columns.units.gyro = std::string(u.name);
    const Measurement m = read_measurement_csv(dir / "g.csv", columns);
    for (int k = 0; k < 5; ++k) EXPECT_NEAR(m.gyro_dph[static_cast<std::size_t>(k)], 7.0 + 0.01 * k, 1e-12);
  }
}

}  // namespace
}  // namespace gyrotherm::fit

namespace gyrotherm::fit {
namespace {

// deg/min: 1 °/min is 60 °/h; a log in °/min fits as the same log in °/h.
TEST(Units, DegreesPerMinute) {
  EXPECT_EQ(in_base(Quantity::gyro, "deg/min", 1.0), 60.0);
  ScratchDir dir;
  testing::simulate_shipped(dir, "warmup", "", "dph.csv");
  ASSERT_EQ(testing::run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"} /^#/{print;next} /^time/{$6=\"gyro_dpm\"; print; next} "
                                    "{$6=sprintf(\"%.12g\",$6/60); print}' dph.csv | tee dpm.csv").exit_code, 0);
  const auto a = testing::run_cli(dir, "fit dph.csv --json");
  const auto b = testing::run_cli(dir, "fit dpm.csv --gyro-col gyro_dpm --gyro-unit deg/min --json");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  for (const char* term : {"1", "T", "T^2", "dT"})
    EXPECT_NEAR(jb["coefficients"][term].get<double>(), ja["coefficients"][term].get<double>(),
                1e-6 * std::abs(ja["coefficients"][term].get<double>()))
        << term;
  EXPECT_EQ(jb["pipeline"]["columns"]["units"]["gyro"], "deg/min");
}

}  // namespace
}  // namespace gyrotherm::fit
