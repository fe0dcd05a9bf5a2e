#pragma once
// Does what was read look like the unit it was read in? A column read in the
// wrong unit gives numbers that no gyro, clock or test produces; these
// checks say so (as cautions every report prints) instead of fitting them:
//
//   gyro:  the white noise of consecutive samples, as an angle random walk
//          N = √(mean((Δg)²·Δt/2)) / 60 °/√h over pairs less than a minute
//          apart (white noise of density q has Var(g) = q/Δt per sample, so
//          (Δg)²·Δt/2 estimates q whatever the rate; slow drift cancels).
//          Below 2e-5 °/√h is quieter than the best strategic-grade gyros
//          (about 1e-4): numbers in rad/s or °/s read as °/h. Above 200 °/√h
//          is noisier than any MEMS gyro (0.1–10): °/h read as °/s.
//   time:  a record longer than 30 days: milliseconds or microseconds read as s.
//   motion: |gyro| above 10 °/s on more than 1 % of the samples (no gyro at
//          rest has such a bias): the vehicle turned, smoothly (a turn at a
//          steady rate hardly changes from sample to sample).
//   temperature: every sample below −100 °C or above 200 °C: °C read as K
//          (−253 °C) or raw counts.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "fit/data/measurement.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

// A gyro at rest reads its bias: a few °/s at most for an uncalibrated MEMS
// part. Beyond kRestRateDph on more than kMovingShare of the samples, it turned.
inline constexpr double kRestRateDph = 10.0 * 3600.0;
inline constexpr double kMovingShare = 0.01;

struct ReadSummary {
  double arw_deg_per_sqrt_h = 0;          // the gyro's white noise (above); 0 without two close samples
  double span_s = 0;                      // last − first sample time
  double temp_min_c = 0, temp_max_c = 0;  // of the temperature as read
  double moving_share = 0;                // samples whose |gyro| exceeds a rest rate (10 °/s)
  double largest_rate_dph = 0;            // the largest |gyro| read
  double gravity_mps2 = 0;                // accel_magnitude: the three axes' median magnitude, m/s² as read
  bool operator==(const ReadSummary&) const = default;
};

// What the checks are judged on, gathered one sample at a time (s, °C, °/h),
// by the in-memory and the one-pass readers alike.
class ReadProbe {
 public:
  void add(double time_s, double temp_c, double gyro_dph);
  ReadSummary summary() const;

 private:
  ReadSummary read_;
  double first_time_ = 0.0, last_time_ = 0.0, last_gyro_ = 0.0, sum_ = 0.0;
  std::size_t samples_ = 0, pairs_ = 0, moving_ = 0;
};

// A sign that a column was read in another unit than its own (or that the
// gyro turned), with the numbers that show it; caution_text words it.
enum class CautionKind {
  gyro_too_quiet,      // white noise below any gyro built: rad/s or °/s read as °/h?
  vehicle_turned,      // in a log's stated unit, sample-to-sample changes no gyro's noise makes
  gyro_turning,        // large rates on many samples: it turned, or a smaller unit
  gyro_too_noisy,      // white noise above any MEMS gyro: °/h read as °/s?
  span_too_long,       // a record of more than 30 days: ms or µs read as s?
  temperature_outside,  // every temperature below −100 °C or above 200 °C: K, or raw counts?
  reading_outside,      // another sensor's reading outside what it reads (hPa read as Pa, µT as gauss?)
  accel_moving,         // an accelerometer's sample-to-sample changes no accelerometer's noise makes: it moved
  accel_magnitude       // an accelerometer's three axes make no gravity (|a| far from 9.81 m/s²): g read as m/s²?
};
struct UnitCaution {
  CautionKind kind = CautionKind::gyro_too_quiet;
  ReadSummary read;  // the numbers judged
  // The column's unit as read, and what chose it (Units::*_from; empty: the default).
  std::string unit, unit_source;
  bool unit_from_log_format = false;  // the unit is the one a log format states
  const SensorKind* sensor = nullptr;  // the measured column's kind (reading_outside: whose reading)
  bool operator==(const UnitCaution&) const = default;
};
std::string caution_text(const UnitCaution& caution);
std::vector<std::string> caution_texts(const std::vector<UnitCaution>& cautions);

// The cautions for a record read in `units` (empty when all looks right).
std::vector<UnitCaution> unit_cautions(const Units& units, const ReadSummary& read);

// An accelerometer's three axes read in `units` (each its window means, m/s²,
// as many of each): at rest or in flight their magnitude is gravity's on
// average. A median magnitude under half or over twice 9.81 m/s² is a unit
// misread (g or mg read as m/s², m/s² read as g), cautioned as
// accel_magnitude; none when a log's format states the unit, or the axes'
// windows differ in number.
std::optional<UnitCaution> gravity_caution(const Units& units, const std::vector<std::vector<double>>& axes);

// "time ms (header 'time (ms)'), …; converted: …": the units read and what chose them.
std::string units_read(const Units& units);
// "  units: {units_read}\n" (unless with_units is false: a report of several
// channels read alike says it once) and a "  caution: …" line each.
std::string units_text(const Units& units, const std::vector<UnitCaution>& cautions, bool with_units = true);
// A multi-channel report's one units line: "units (every channel): …\n" when
// every channel was read in the same units, else "".
template <class Channels, class UnitsOf>
std::string shared_units_text(const Channels& channels, UnitsOf units_of) {
  if (channels.size() < 2) return {};
  const std::string first = units_read(units_of(channels.front()));
  for (const auto& c : channels)
    if (units_read(units_of(c)) != first) return {};
  return "units (every channel): " + first + "\n";
}

// The summary and cautions of a whole measurement (allan reads one directly).
std::vector<UnitCaution> measurement_cautions(const Measurement& m);

// Runs `work`; an InputError it throws on a record with cautions is thrown
// again with them (a fit that fails on numbers read in the wrong unit — a
// temperature in K makes T and T² collinear — says what looks wrong).
template <class Work>
auto with_cautions(const std::vector<UnitCaution>& cautions, Work&& work) {
  try {
    return work();
  } catch (const InputError& e) {
    if (cautions.empty()) throw;
    std::string message(e.what());
    for (const UnitCaution& c : cautions) message += "\n  caution (how the record was read): " + caution_text(c);
    throw InputError(message);
  }
}

}  // namespace gyrotherm::fit
