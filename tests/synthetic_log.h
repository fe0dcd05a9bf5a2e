#pragma once
// A small synthetic log for tests of how a record is read (units in the
// header, CSV forms): 2 h at 1 Hz, a temperature sine, a linear sensitivity
// and deterministic white noise; and the fit `gyrotherm fit --json` makes of a
// file written from it.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace gyrotherm::testing {

struct LogRow {
  double t, temp_c, gyro_dph;
};

inline std::vector<LogRow> synthetic_log() {
  std::vector<LogRow> rows;
  std::uint64_t state = 12345;
  for (int k = 0; k < 7200; ++k) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
    const double temp = 25.0 + 15.0 * std::sin(2.0 * M_PI * k / 3600.0);
    rows.push_back({static_cast<double>(k), temp, 5.0 + 0.2 * temp + 3.0 * u});
  }
  return rows;
}

// `fit ARGS --model T --json`, parsed; null (and a test failure) when it fails.
inline nlohmann::json fit_json(const ScratchDir& dir, const std::string& args) {
  const auto r = run_cli(dir, "fit " + args + " --model T --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

}  // namespace gyrotherm::testing
