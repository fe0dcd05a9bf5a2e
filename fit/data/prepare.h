#pragma once
// Reading and conditioning a record, the data half of the pipeline
// (fit/pipeline.h has the rest):
//
//   1. read the measurement CSV (fit/data/measurement.h);
//   2. flag counting glitches with a moving-median rule (fit/data/outliers.h);
//   3. average into windows that never span a gap (fit/data/averaging.h);
//   4. the window means' derivatives (fit/data/derivatives.h).
//
// Records too large to hold are prepared by streaming (fit/data/streaming.h).

#include <filesystem>
#include <string>

#include "fit/data/averaging.h"
#include "fit/data/derivatives.h"
#include "fit/data/measurement.h"
#include "fit/data/outliers.h"
#include "fit/data/plausibility.h"

namespace gyrotherm::fit {

struct PipelineOptions {
  ColumnMap columns;
  bool remove_outliers = true;
  OutlierOptions outliers;
  AveragingOptions averaging;
  DerivativeMode derivative = DerivativeMode::central;
  double derivative_span_s = kDefaultDerivativeSpanS;  // --deriv-span (fit/data/derivatives.h)
  double sensor_tau_s = 0.0;  // --sensor-tau: the temperature sensors' lag (fit/data/derivatives.h)
};

struct PreparedData {
  std::string file;
  Units units;  // the units the columns were read in, each set (Measurement::units)
  std::vector<UnitCaution> cautions;  // numbers that look like another unit (fit/data/plausibility.h)
  std::size_t raw_samples = 0;
  OutlierReport outliers;
  AveragingReport averaging;
  AveragedSeries series;
  DerivedSeries derived;
  // As derived (PipelineOptions): the mode, the span and the sensors' lag.
  DerivativeMode derivative = DerivativeMode::central;
  double derivative_span_s = kDefaultDerivativeSpanS;
  double sensor_tau_s = 0.0;
  bool has_temp2() const { return !series.temp2_c.empty(); }
};

// d.derived from d.series by the options' derivatives (and the fields above).
void derive_into(PreparedData& d, const PipelineOptions& options);

PreparedData prepare_data(const Measurement& measurement, const PipelineOptions& options);

// "317 windows of 100 s", or for a bursty record "25 bursts of 5 s every
// 305 s, each averaged as one window (shorter than the 100 s window)".
std::string describe_windows(const PreparedData& data, const PipelineOptions& options);
// What the instability is the standard deviation of: "100 s averages" or "the burst means".
std::string averages_name(const PreparedData& data, const PipelineOptions& options);
PreparedData prepare_data(const std::filesystem::path& csv, const PipelineOptions& options);

}  // namespace gyrotherm::fit
