#include "fit/data/plausibility.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "fit/data/autopilot_log.h"

namespace gyrotherm::fit {
namespace {

constexpr double kPairWithinS = 60.0;
constexpr double kQuietestArw = 2e-5;  // °/√h
constexpr double kNoisiestArw = 200.0;
// An accelerometer's white noise as a velocity random walk (m/s/√h, 3600 ×
// the gyro-convention figure the probe computes): MEMS parts lie between
// about 0.02 and 0.5 (20 to 400 µg/√Hz); above this, 20 times the noisiest,
// the changes are motion or vibration (a flying vehicle: about 100).
constexpr double kNoisiestVrw = 5.0;
constexpr double kLongestSpanS = 30.0 * 86400.0;
constexpr double kColdestC = -100.0, kHottestC = 200.0;

// What another sensor reads at most, in its base unit, beyond which the
// numbers are in a smaller unit than read (or below which a larger one), and
// the unit they then look like.
struct SensorLimits {
  double low_from, low_to;  // a largest reading in [low_from, low_to): a larger unit read as the base?
  double largest;           // above: a smaller unit read as the base?
  const char* low_looks;    // what a low largest reading looks like
  const char* high_looks;
};
const SensorLimits* sensor_limits(const SensorKind& kind) {
  // An accelerometer: up to a few hundred g on a shock sensor (2000 m/s²).
  static constexpr SensorLimits kAccel{0.0, 0.0, 2000.0, "", "mg or ug read as m/s²"};
  // A barometer: 110 kPa at sea level, 200 kPa in a pressure chamber; an
  // atmosphere written in hPa (300..1100) read as Pa looks like a partial
  // vacuum (a chamber's vacuum, below 300 Pa, is left alone).
  static constexpr SensorLimits kBaro{300.0, 1200.0, 2e5, "an atmosphere written in hPa or mbar read as Pa",
                                      "a smaller unit read as Pa"};
  // A magnetometer near the Earth: 0.25..0.65 gauss, a board's own field
  // more; none reads above 20 gauss, or only below 1e-3 gauss.
  static constexpr SensorLimits kMag{0.0, 1e-3, 20.0, "tesla read as gauss", "milligauss, uT or nT read as gauss"};
  if (kind.quantity == Quantity::accel) return &kAccel;
  if (kind.quantity == Quantity::pressure) return &kBaro;
  if (kind.quantity == Quantity::magnetic) return &kMag;
  return nullptr;
}

}  // namespace

void ReadProbe::add(double time_s, double temp_c, double gyro_dph) {
  if (samples_++ == 0) {
    first_time_ = time_s;
    read_.temp_min_c = read_.temp_max_c = temp_c;
  } else if (const double dt = time_s - last_time_; dt > 0.0 && dt < kPairWithinS) {
    const double dg = gyro_dph - last_gyro_;
    sum_ += dg * dg * dt / 2.0;
    ++pairs_;
  }
  read_.span_s = time_s - first_time_;
  moving_ += std::abs(gyro_dph) > kRestRateDph;
  read_.largest_rate_dph = std::max(read_.largest_rate_dph, std::abs(gyro_dph));
  read_.temp_min_c = std::min(read_.temp_min_c, temp_c);
  read_.temp_max_c = std::max(read_.temp_max_c, temp_c);
  last_time_ = time_s;
  last_gyro_ = gyro_dph;
}

ReadSummary ReadProbe::summary() const {
  ReadSummary out = read_;
  out.arw_deg_per_sqrt_h = pairs_ == 0 ? 0.0 : std::sqrt(sum_ / static_cast<double>(pairs_)) / 60.0;
  out.moving_share = samples_ == 0 ? 0.0 : static_cast<double>(moving_) / static_cast<double>(samples_);
  return out;
}

std::vector<UnitCaution> unit_cautions(const Units& u, const ReadSummary& r) {
  std::vector<UnitCaution> out;
  const auto caution = [&](CautionKind kind, std::string_view unit, const std::string& source) {
    out.push_back(UnitCaution{kind, r, std::string(unit), source, stated_by_log_format(source), &u.kind()});
  };
  const double n = r.arw_deg_per_sqrt_h;
  const std::string_view gyro = u.gyro_unit().name;
  if (u.kind().is_gyro) {  // (the rate and angle-random-walk limits are a gyro's)
    if (n > 0.0 && n < kQuietestArw) caution(CautionKind::gyro_too_quiet, gyro, u.gyro_from);
    if (n > kNoisiestArw && stated_by_log_format(u.gyro_from))  // the format states the unit: the gyro turned
      caution(CautionKind::vehicle_turned, gyro, u.gyro_from);
    else if (r.moving_share > kMovingShare)  // smooth turns: large rates, small sample-to-sample changes
      caution(CautionKind::gyro_turning, gyro, u.gyro_from);
    else if (n > kNoisiestArw)
      caution(CautionKind::gyro_too_noisy, gyro, u.gyro_from);
  } else {
    if (u.kind().quantity == Quantity::accel && 3600.0 * n > kNoisiestVrw)
      caution(CautionKind::accel_moving, gyro, u.gyro_from);
    if (const SensorLimits* limits = sensor_limits(u.kind());
        limits != nullptr && r.largest_rate_dph > 0.0 &&
        (r.largest_rate_dph > limits->largest ||
         (r.largest_rate_dph >= limits->low_from && r.largest_rate_dph < limits->low_to)))
      caution(CautionKind::reading_outside, gyro, u.gyro_from);
  }
  if (r.span_s > kLongestSpanS) caution(CautionKind::span_too_long, u.time_unit().name, u.time_from);
  if (r.temp_max_c < kColdestC || r.temp_min_c > kHottestC)
    caution(CautionKind::temperature_outside, u.temp_unit().name, u.temp_from);
  return out;
}

std::optional<UnitCaution> gravity_caution(const Units& u, const std::vector<std::vector<double>>& axes) {
  if (u.kind().quantity != Quantity::accel || axes.size() != 3 || stated_by_log_format(u.gyro_from)) return std::nullopt;
  const std::size_t n = axes[0].size();
  if (n == 0 || axes[1].size() != n || axes[2].size() != n) return std::nullopt;
  std::vector<double> magnitude(n);
  for (std::size_t i = 0; i < n; ++i) magnitude[i] = std::hypot(axes[0][i], axes[1][i], axes[2][i]);
  std::nth_element(magnitude.begin(), magnitude.begin() + static_cast<std::ptrdiff_t>(n / 2), magnitude.end());
  const double median = magnitude[n / 2];
  if (median >= 0.5 * kStandardGravity && median <= 2.0 * kStandardGravity) return std::nullopt;
  ReadSummary r;
  r.gravity_mps2 = median;
  return UnitCaution{CautionKind::accel_magnitude, r, std::string(u.gyro_unit().name), u.gyro_from, false, &u.kind()};
}

std::string caution_text(const UnitCaution& c) {
  const ReadSummary& r = c.read;
  const double n = r.arw_deg_per_sqrt_h;
  const std::string source = c.unit_source.empty() ? "default" : c.unit_source;
  const std::string read_in = fmt::format("read in {} ({})", c.unit, source);
  switch (c.kind) {
    case CautionKind::gyro_too_quiet:
      return fmt::format(
          "the gyro's sample-to-sample noise is an angle random walk of {:.2g} °/√h, quieter than any gyro "
          "built (the best reach about 1e-4): {}, are its numbers really in that unit (rad/s or °/s read "
          "as °/h?); give --gyro-unit",
          n, read_in);
    case CautionKind::vehicle_turned:
      return fmt::format(
          "the gyro's sample-to-sample changes are an angle random walk of {:.3g} °/√h, more than any MEMS gyro's "
          "noise (0.1 to 10), in the unit the log's format states ({}): the vehicle turned, and a rotation is read "
          "as bias; a thermal test holds the gyro still",
          n, c.unit_source);
    case CautionKind::gyro_turning:
      return fmt::format(
          "the gyro reads more than {:g} °/s on {:.0f} % of the samples (up to {:.3g} °/s, {}): no gyro at rest "
          "has such a bias, so {}; a thermal test holds the gyro still",
          kRestRateDph / 3600.0, 100.0 * r.moving_share, r.largest_rate_dph / 3600.0, read_in,
          c.unit_from_log_format ? "the vehicle turned, and a rotation is read as bias"
                                 : "it turned (a rotation is read as bias), or its numbers are in a smaller unit "
                                   "than that (°/h read as °/s?)");
    case CautionKind::gyro_too_noisy:
      return fmt::format(
          "the gyro's sample-to-sample noise is an angle random walk of {:.3g} °/√h, noisier than any MEMS "
          "gyro (0.1 to 10): {}, are its numbers really in that unit (°/h read as °/s?); give --gyro-unit",
          n, read_in);
    case CautionKind::span_too_long:
      return fmt::format(
          "the record spans {:.0f} days, {}: if the test was shorter, the time column is in another unit "
          "(ms or us?); give --time-unit",
          r.span_s / 86400.0, read_in);
    case CautionKind::temperature_outside: {
      // The unit the numbers look like: kelvin read as °C sit near 250..350
      // "°C"; °C read as kelvin near −273 + (−60..150) °C.
      const bool kelvin_as_celsius = c.unit == "C" && r.temp_min_c > 200.0 && r.temp_max_c < 400.0;
      const bool celsius_as_kelvin = c.unit == "K" && r.temp_min_c > -340.0 && r.temp_max_c < -100.0;
      const bool guessed = kelvin_as_celsius || celsius_as_kelvin;
      // A unit the column's name states cannot be overruled by --temp-unit;
      // an offset reads the numbers under the name.
      const bool named = source.starts_with("header");
      const std::string unit =
          kelvin_as_celsius
              ? fmt::format("the numbers look like kelvin read as °C (give {})",
                            named ? "--temp-offset -273.15: the column's name says °C" : "--temp-unit K")
          : celsius_as_kelvin
              ? fmt::format("the numbers look like °C read as kelvin (give {})",
                            named ? "--temp-offset 273.15: the column's name says K" : "--temp-unit C")
              : std::string("is the column in another unit (give --temp-unit)");
      return fmt::format(
          "every temperature is {} ({:.4g}..{:.4g} °C, {}): {} or raw counts (give --temp-scale and "
          "--temp-offset: temperature = A x column + B){}",
          r.temp_max_c < kColdestC ? "below -100 °C" : "above 200 °C", r.temp_min_c, r.temp_max_c, read_in, unit,
          guessed ? "" : "?");
    }
    case CautionKind::accel_moving:
      return fmt::format(
          "the accelerometer's sample-to-sample changes are a velocity random walk of {:.3g} m/s/√h, more than any "
          "MEMS accelerometer's noise (about 0.02 to 0.5), {}: {}; a thermal test holds the accelerometer still",
          3600.0 * n, c.unit_from_log_format ? fmt::format("in the unit the log's format states ({})", c.unit_source) : read_in,
          c.unit_from_log_format ? "the vehicle moved or vibrated, and its motion is read as bias"
                                 : "it moved or vibrated (motion is read as bias), or its numbers are in a smaller "
                                   "unit than that (mg read as m/s²?)");
    case CautionKind::accel_magnitude: {
      // The accelerometer unit that would put the magnitude nearest gravity's.
      const Unit& read_unit = find_unit(Quantity::accel, c.unit, "");
      const Unit* best = &read_unit;
      for (const Unit& unit : unit_table())
        if (unit.quantity == Quantity::accel &&
            std::abs(std::log(r.gravity_mps2 / read_unit.factor * unit.factor / kStandardGravity)) <
                std::abs(std::log(r.gravity_mps2 / read_unit.factor * best->factor / kStandardGravity)))
          best = &unit;
      return fmt::format(
          "the accelerometer's three axes have a median magnitude of {:.3g} m/s² ({}), where gravity alone is 9.81: "
          "at rest or in flight they read gravity on average{}",
          r.gravity_mps2, read_in,
          best != &read_unit ? fmt::format("; are its numbers in {} ({})? give --gyro-unit {}", best->name,
                                           best->meaning, best->name)
                             : std::string("; is the unit or the scale right?"));
    }
    case CautionKind::reading_outside: {
      const SensorLimits* found = c.sensor != nullptr ? sensor_limits(*c.sensor) : nullptr;
      if (found == nullptr) return {};
      const SensorLimits& limits = *found;
      const bool above = r.largest_rate_dph > limits.largest;
      // Read in another unit than the base one: the numbers are in a smaller (larger) unit than that one.
      const bool base = c.unit == base_unit(c.sensor->quantity);
      const std::string looks = base ? std::string(above ? limits.high_looks : limits.low_looks)
                                     : fmt::format("numbers in a {} unit than {}", above ? "smaller" : "larger", c.unit);
      return fmt::format("the {}'s largest reading is {:.4g} {}, {} ({}): {}? give the --gyro-unit they are in",
                         c.sensor->noun, r.largest_rate_dph, c.sensor->unit,
                         above ? fmt::format("more than any {} reads ({:g} {})", c.sensor->noun, limits.largest,
                                             c.sensor->unit)
                               : fmt::format("under {:g} {}", limits.low_to, c.sensor->unit),
                         read_in, looks);
    }
  }
  return {};
}

std::vector<std::string> caution_texts(const std::vector<UnitCaution>& cautions) {
  std::vector<std::string> out;
  for (const UnitCaution& c : cautions) out.push_back(caution_text(c));
  return out;
}

std::string units_read(const Units& units) {
  return units.used() + (units.identity() ? std::string() : "; converted: " + units.description());
}

std::string units_text(const Units& units, const std::vector<UnitCaution>& cautions, bool with_units) {
  std::string out = with_units ? fmt::format("  units: {}\n", units_read(units)) : std::string();
  for (const UnitCaution& c : cautions) out += "  caution: " + caution_text(c) + "\n";
  return out;
}

std::vector<UnitCaution> measurement_cautions(const Measurement& m) {
  ReadProbe probe;
  for (std::size_t k = 0; k < m.size(); ++k) probe.add(m.time_s[k], m.temp_c[k], m.gyro_dph[k]);
  return unit_cautions(m.units, probe.summary());
}

}  // namespace gyrotherm::fit
