#include "fit/data/plausibility.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gyrotherm::fit {
namespace {

constexpr double kPairWithinS = 60.0;
constexpr double kQuietestArw = 2e-5;  // °/√h
constexpr double kNoisiestArw = 200.0;
constexpr double kLongestSpanS = 30.0 * 86400.0;
constexpr double kColdestC = -100.0, kHottestC = 200.0;

}  // namespace

void WhiteNoiseProbe::add(double time_s, double gyro_dph) {
  if (started_) {
    const double dt = time_s - last_time_;
    if (dt > 0.0 && dt < kPairWithinS) {
      const double dg = gyro_dph - last_gyro_;
      sum_ += dg * dg * dt / 2.0;
      ++pairs_;
    }
  }
  started_ = true;
  last_time_ = time_s;
  last_gyro_ = gyro_dph;
}

double WhiteNoiseProbe::arw_deg_per_sqrt_h() const {
  return pairs_ == 0 ? 0.0 : std::sqrt(sum_ / static_cast<double>(pairs_)) / 60.0;
}

std::vector<std::string> unit_cautions(const Units& u, const ReadSummary& r) {
  std::vector<std::string> out;
  const double n = r.arw_deg_per_sqrt_h;
  const std::string gyro_read = fmt::format("read in {} ({})", u.gyro_unit().name, u.gyro_from.empty() ? "default" : u.gyro_from);
  if (n > 0.0 && n < kQuietestArw)
    out.push_back(fmt::format(
        "the gyro's sample-to-sample noise is an angle random walk of {:.2g} °/√h, quieter than any gyro "
        "built (the best reach about 1e-4): {}, are its numbers really in that unit (rad/s or °/s read "
        "as °/h?); give --gyro-unit",
        n, gyro_read));
  if (n > kNoisiestArw)
    out.push_back(fmt::format(
        "the gyro's sample-to-sample noise is an angle random walk of {:.3g} °/√h, noisier than any MEMS "
        "gyro (0.1 to 10): {}, are its numbers really in that unit (°/h read as °/s?); give --gyro-unit",
        n, gyro_read));
  if (r.span_s > kLongestSpanS)
    out.push_back(fmt::format(
        "the record spans {:.0f} days, read in {} ({}): if the test was shorter, the time column is in "
        "another unit (ms or us?); give --time-unit",
        r.span_s / 86400.0, u.time_unit().name, u.time_from.empty() ? "default" : u.time_from));
  if (r.temp_max_c < kColdestC || r.temp_min_c > kHottestC)
    out.push_back(fmt::format(
        "every temperature is {} ({:.4g}..{:.4g} °C, read in {} ({})): is the column in another unit "
        "(°C read as K?) or raw counts (give --temp-scale and --temp-offset)?",
        r.temp_max_c < kColdestC ? "below -100 °C" : "above 200 °C", r.temp_min_c, r.temp_max_c,
        u.temp_unit().name, u.temp_from.empty() ? "default" : u.temp_from));
  return out;
}

std::string units_text(const Units& units, const std::vector<std::string>& cautions) {
  std::string out = fmt::format("  units: {}{}\n", units.used(),
                                units.identity() ? std::string() : "; converted: " + units.description());
  for (const std::string& c : cautions) out += "  caution: " + c + "\n";
  return out;
}

std::vector<std::string> measurement_cautions(const Measurement& m) {
  ReadSummary r;
  WhiteNoiseProbe probe;
  for (std::size_t k = 0; k < m.size(); ++k) probe.add(m.time_s[k], m.gyro_dph[k]);
  r.arw_deg_per_sqrt_h = probe.arw_deg_per_sqrt_h();
  if (m.size() > 0) {
    r.span_s = m.time_s.back() - m.time_s.front();
    const auto [lo, hi] = std::minmax_element(m.temp_c.begin(), m.temp_c.end());
    r.temp_min_c = *lo;
    r.temp_max_c = *hi;
  }
  return unit_cautions(m.units, r);
}

}  // namespace gyrotherm::fit
