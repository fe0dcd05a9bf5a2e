#pragma once
// Records as named columns for the tests of fit/data/table.h and
// studies/record_source.h: a synthetic thermal record, its CSV (numbers
// written with 17 significant digits, so that the reader gets the very same
// doubles), a table over a CSV as the reader read it, and checks that two
// prepared records are the same to the last bit.

#include <tuple>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/data/table.h"

namespace gyrotherm::testing {

// Columns owned by the test, lent to a fit::Table.
struct OwnedColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;

  void add(std::string name, std::vector<double> v) {
    names.push_back(std::move(name));
    values.push_back(std::move(v));
  }
  std::vector<double>& operator[](const std::string& name) {
    for (std::size_t c = 0; c < names.size(); ++c)
      if (names[c] == name) return values[c];
    throw std::out_of_range(name);
  }
  fit::Table table(std::string name = "arrays") const {
    fit::Table t;
    t.name = std::move(name);
    for (std::size_t c = 0; c < names.size(); ++c) t.columns.push_back({names[c], values[c].data(), values[c].size()});
    return t;
  }
  // Comma-separated, every number as "%.17g" (read back exactly).
  void write_csv(const std::filesystem::path& csv) const {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(csv.c_str(), "wb"), &std::fclose);
    ASSERT_TRUE(out) << csv;
    std::string line;
    for (std::size_t c = 0; c < names.size(); ++c) line += (c ? "," : "") + names[c];
    std::fputs((line + "\n").c_str(), out.get());
    const std::size_t rows = values.empty() ? 0 : values.front().size();
    for (std::size_t k = 0; k < rows; ++k) {
      line.clear();
      for (std::size_t c = 0; c < values.size(); ++c) line += fmt::format("{}{:.17g}", c ? "," : "", values[c][k]);
      line += '\n';
      std::fputs(line.c_str(), out.get());
    }
  }
};

// `rows` samples at `rate_hz` of a gyro in a chamber cycling ±30 °C about
// 20 °C every 6 h: gyro = −7 − 3e-2·T + 1e-3·T² + 20·dT/dt (°C/s) + white
// noise of 0.5 °/h, and about one glitch of ±25 °/h per 5000 samples; a
// second sensor 0.3 °C behind, and a heater power column. From `seed`.
inline OwnedColumns thermal_record(std::size_t rows, double rate_hz, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::uniform_int_distribution<int> glitch(0, 4999);
  std::vector<double> t(rows), temp(rows), temp2(rows), gyro(rows), heater(rows);
  const double w = 2.0 * M_PI / (6.0 * 3600.0);
  for (std::size_t k = 0; k < rows; ++k) {
    t[k] = 1000.0 + static_cast<double>(k) / rate_hz;
    temp[k] = 20.0 + 30.0 * std::sin(w * t[k]);
    const double rate_c_per_s = 30.0 * w * std::cos(w * t[k]);
    temp2[k] = temp[k] - 0.3 * std::cos(w * t[k]);
    heater[k] = 5.0 + 4.0 * std::sin(3.0 * w * t[k]);
    gyro[k] = -7.0 - 3e-2 * temp[k] + 1e-3 * temp[k] * temp[k] + 20.0 * rate_c_per_s + noise(rng);
    if (glitch(rng) == 0) gyro[k] += (k % 2 ? 25.0 : -25.0);
  }
  OwnedColumns c;
  c.add("time_s", std::move(t));
  c.add("temp_c", std::move(temp));
  c.add("gyro_dph", std::move(gyro));
  c.add("temp2_c", std::move(temp2));
  c.add("heater_w", std::move(heater));
  return c;
}

// The numeric columns of a CSV as the reader reads them (in s, °C and °/h:
// for a log whose units are the base ones), in the header's order.
inline OwnedColumns columns_of_csv(const std::filesystem::path& csv) {
  fit::ColumnMap all;
  all.other_numeric = true;
  const fit::Measurement m = fit::read_measurement_csv(csv, all);
  OwnedColumns c;
  for (const std::string& name : m.columns) {
    if (name == all.time) c.add(name, m.time_s);
    else if (name == all.temp) c.add(name, m.temp_c);
    else if (name == all.gyro) c.add(name, m.gyro_dph);
    else if (name == all.temp2 && m.has_temp2()) c.add(name, m.temp2_c);
    else if (const auto it = m.extra.find(name); it != m.extra.end()) c.add(name, it->second);
  }
  return c;
}

// Two prepared records the same to the last bit, but for their names.
inline void expect_identical(const fit::PreparedData& a, const fit::PreparedData& b) {
  // Compared field group by field group (a tuple of references each).
  const auto report = [](const fit::PreparedData& d) {
    const fit::AveragingReport& r = d.averaging;
    return std::tie(d.raw_samples, d.cautions, d.outliers.removed, d.outliers.times_s, d.outliers.floor_dph,
                    d.outliers.scale_dph, r.sample_interval_s, r.dropped_windows, r.bursts, r.median_run_s,
                    r.median_spacing_s, d.derivative_span_s);
  };
  const auto series = [](const fit::AveragedSeries& s) {
    return std::tie(s.window_s, s.start_time_s, s.time_s, s.temp_c, s.gyro_dph, s.temp2_c, s.samples, s.gyro_sd_dph,
                    s.gyro_lag1, s.run, s.extra);
  };
  const auto derived = [](const fit::DerivedSeries& d) {
    return std::tie(d.time_s, d.temp_c, d.rate_c_per_s, d.accel_c_per_s2, d.temp2_c, d.extra);
  };
  EXPECT_EQ(a.units.used() + a.units.description(), b.units.used() + b.units.description());
  EXPECT_TRUE(report(a) == report(b));
  EXPECT_TRUE(series(a.series) == series(b.series));
  EXPECT_TRUE(derived(a.derived) == derived(b.derived));
  ASSERT_EQ(a.averaging.gaps.size(), b.averaging.gaps.size());
  for (std::size_t g = 0; g < a.averaging.gaps.size(); ++g)
    EXPECT_TRUE(std::tie(a.averaging.gaps[g].from_s, a.averaging.gaps[g].to_s) ==
                std::tie(b.averaging.gaps[g].from_s, b.averaging.gaps[g].to_s));
}

}  // namespace gyrotherm::testing
