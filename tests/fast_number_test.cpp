// The fast number writer (sim/util/fast_number.h) gives exactly fmt's digits,
// and simulate's CSV is byte for byte what the format string gave.

#include "sim/util/fast_number.h"

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "sim/config_loader.h"
#include "sim/output.h"
#include "sim/simulator.h"

namespace gyrotherm {
namespace {

std::string fixed(double v, int d) {
  char buffer[400];
  return std::string(buffer, write_fixed(buffer, v, d));
}

TEST(FastNumber, FixedGivesFmtsDigits) {
  boost::random::mt19937_64 rng(3);
  boost::random::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const double v = unit(rng) * std::pow(10.0, static_cast<double>(i % 15) - 6.0);
    const int d = i % 10;
    ASSERT_EQ(fixed(v, d), fmt::format("{:.{}f}", v, d)) << v << " with " << d;
  }
  // Ties and near-ties in decimal, where the exact binary value decides.
  for (int d = 0; d <= 9; ++d)
    for (int k = -2000; k <= 2000; ++k) {
      const double tie = (k + 0.5) / std::pow(10.0, d);
      for (const double v : {tie, std::nextafter(tie, 0.0), std::nextafter(tie, 1e9), tie * 1000.0 + 0.5})
        ASSERT_EQ(fixed(v, d), fmt::format("{:.{}f}", v, d)) << v << " with " << d;
    }
  for (const double v : {0.0, -0.0, -1e-9, 1e-9, -0.000004, 123456789.123456789, 1e300, -1e300,
                         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::quiet_NaN(), 9007199254740993.0, 4503599627370495.5})
    for (int d : {0, 5, 9})
      EXPECT_EQ(fixed(v, d), fmt::format("{:.{}f}", v, d)) << v << " with " << d;
}

TEST(FastNumber, GeneralGivesFmtsDigits) {
  boost::random::mt19937_64 rng(4);
  boost::random::uniform_real_distribution<double> unit(0.0, 1.0);
  char buffer[400];
  for (int i = 0; i < 100000; ++i) {
    const double v = std::floor(unit(rng) * std::pow(10.0, i % 12)) / (i % 3 == 0 ? 1.0 : 100.0);
    ASSERT_EQ(std::string(buffer, write_general(buffer, v, 10)), fmt::format("{:.10g}", v)) << v;
  }
}

TEST(FastNumber, SimulatedCsvIsByteForByteTheFormatString) {
  sim::Scenario sc = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml");
  const sim::Simulator simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file));
  const sim::SimulationResult r = simulator.run();
  std::string expected = fmt::format("# gyrotherm simulate: scenario {}, seed {}\n", sc.name, r.seed);
  expected += "# truth (noise-free bias, true coefficients) in the .truth.json beside this file\n";
  expected += "time_s,chamber_c,case_c,temp_c,temp2_c,gyro_dph,bias_true_dph\n";
  for (std::size_t k = 0; k < r.rows(); ++k)
    expected += fmt::format("{:.10g},{:.5f},{:.5f},{:.5f},{:.5f},{:.6f},{:.9f}\n", r.time_s[k], r.chamber_c[k],
                            r.case_c[k], r.temp_c[k], r.temp2_c[k], r.gyro_dph[k], r.bias_true_dph[k]);
  EXPECT_TRUE(sim::simulation_csv(simulator, r) == expected);
}

}  // namespace
}  // namespace gyrotherm
