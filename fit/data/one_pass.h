#pragma once
// The one-pass preparation of fit/data/streaming.h (prefix, glitch filter,
// averager, one row at a time), for the readers that feed it: a CSV's rows
// from a reading thread (fit/data/streaming.cpp) and a caller's arrays
// (fit/data/table.cpp). Internal to fit/data.

#include <optional>
#include <string>
#include <vector>

#include "fit/data/hampel.h"
#include "fit/data/measurement.h"
#include "fit/data/plausibility.h"
#include "fit/data/prepare.h"
#include "fit/data/streaming.h"

namespace gyrotherm::fit::one_pass {

// One row, after the units are applied: time s, temp °C, gyro °/h, temp2 °C
// (0 without that column).
using Row = RowValues;

// What the prefix fixes for the rest of the record.
struct RecordRules {
  double interval_s = 0;  // Δ
  double floor_dph = 0;   // s_floor
  double zero_dph = 0;    // round-off level
  bool judge = false;     // at least 3 samples (fit/data/outliers.cpp judges none otherwise)
  bool bursts = false;
};

// The one-pass preparation (fit/data/streaming.h): prefix, then filter and averager, one row at a
// time. `options` must outlive it; validate its outlier and averaging options first.
class Preparer {
 public:
  Preparer(const PipelineOptions& options, std::string file) : o_(options) { d_.file = std::move(file); }

  // Before the first row: the units and whether there is a second temperature.
  void set_header(const CsvHeader& header) {
    has_temp2_ = header.has_temp2;
    d_.units = header.units;
  }
  void add(const Row& r) {
    ++d_.raw_samples;
    probe_.add(r.t, r.temp, r.gyro);
    if (!averager_) {
      if (prefix_.empty()) prefix_.reserve(kPrefixRows);  // once: no copies and fresh pages as it grows
      prefix_.push_back(r);
      if (prefix_.size() == kPrefixRows) begin_stream(false);
      return;
    }
    stream(r);
  }
  // Throws InputError (naming the file) for a record of fewer than 2 rows or
  // one no window survives.
  PreparedData finish();

 private:
  // The rules from the prefix (the whole record if `whole`), then the prefix
  // replayed through the filter.
  void begin_stream(bool whole);
  void stream(const Row& r) {
    if (!rules_.judge) {
      averager_->add(r.t, r.temp, r.gyro, r.temp2, true);
      return;
    }
    filter_->add(r.t, r.gyro, r, [this](const Row& row, bool kept) { judged(row, kept); });
  }
  // A sample the glitch rule has judged goes to the averager.
  void judged(const Row& r, bool kept) {
    if (!kept) d_.outliers.times_s.push_back(r.t);
    averager_->add(r.t, r.temp, r.gyro, r.temp2, kept);
  }

  const PipelineOptions& o_;
  PreparedData d_;
  ReadProbe probe_;  // what the units' plausibility is judged on
  bool has_temp2_ = false;
  std::vector<Row> prefix_;
  RecordRules rules_;
  std::optional<WindowAverager> averager_;
  std::optional<CentredHampel<Row>> filter_;  // the glitch rule (fit/data/hampel.h)
};

}  // namespace gyrotherm::fit::one_pass
