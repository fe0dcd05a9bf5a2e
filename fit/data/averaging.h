#pragma once
// Averaging the samples into windows of W seconds that never span a gap (the
// paper's 100 s averages).
//
// With Δ the sample interval (the median time step of the record):
//
//   1. A step t_k − t_{k−1} larger than gap_factor · Δ, or larger than W, is a
//      gap: it ends a gap-free run, and sample k starts the next run at r = t_k.
//   2. Within a run the windows are [r + jW, r + (j+1)W), j = 0, 1, …
//   3. A window's time, temperatures and gyro output are the plain means of its
//      valid samples (valid[k] ≠ 0; invalid samples are never averaged).
//   4. A window with fewer valid samples than min_fill · W/Δ is dropped; this
//      drops the partial last window of every run (and windows mostly made of
//      rejected glitches).
//
// Bursty records. A logger that records in bursts (the PAN log: 5 s of 50 Hz
// every 305 s) has gap-free runs shorter than any useful window, and rule 4
// would drop them all. When the median run is shorter than W, each run
// becomes one window instead (its mean, at the mean time of its samples; it
// needs min_fill of its own samples valid), and the report says so
// (AveragingReport::bursts). average_windows decides this from the whole
// record; the streaming reader keeps plain windows.
//
// The work is done by WindowAverager, which sees one sample at a time and keeps
// only the current window, so a streaming reader can feed it a record of any
// length (it needs Δ up front: from a first pass, a prefix, or the file's
// nominal rate). average_windows is the in-memory driver.
//
// Reference: Yu, Xu, Wei, Long, Infrared and Laser Engineering 43(1):81-87
// (2014) (1 s samples averaged over 100 s); IEEE Std 952-1997, Annex C (averages of rate data over clusters
// of length τ).

#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fit/data/edge_rate.h"
#include "fit/data/measurement.h"

namespace gyrotherm::fit {

struct AveragingOptions {
  double window_s = 100.0;  // W, the averaging window, s (--avg)
  double gap_factor = 3.0;  // a step longer than gap_factor sample intervals is a gap (> 1)
  double min_fill = 0.5;    // a window needs at least min_fill · W/Δ valid samples (0, 1]

  // Throws InputError naming the option, the value and the rule.
  void validate() const;
};

struct AveragedSeries {
  std::vector<double> time_s;                     // mean time of the samples in each window
  double window_s = 0;  // the windows' length: W, or with bursts the median burst length
  std::vector<double> temp_c, gyro_dph, temp2_c;  // window means (temp2_c empty if absent)
  std::vector<std::size_t> samples;               // valid samples in each window
  // The scatter of the gyro samples inside each window: their standard
  // deviation and lag-1 autocorrelation (consecutive valid samples; 0 when
  // there are too few), for a noise floor from within the windows.
  std::vector<double> gyro_sd_dph, gyro_lag1;
  // The window means of a log's extra columns (Measurement::extra).
  std::map<std::string, std::vector<double>, std::less<>> extra;
  // The window mean of each one's time derivative from the samples at the
  // window's edges (fit/data/edge_rate.h): NaN where a window holds too few
  // samples, and with bursts (each burst's own rate is noise: the rates
  // come from neighbouring bursts, fit/data/derivatives.h). Empty when the
  // series was not made by a WindowAverager.
  // Each with its standard error (EdgeRate::standard_error), in the *_se fields.
  std::vector<double> temp_rate_c_per_s, temp2_rate_c_per_s, temp_rate_se, temp2_rate_se;
  std::map<std::string, std::vector<double>, std::less<>> extra_rate, extra_rate_se;
  std::vector<std::size_t> run;                   // index of the gap-free run the window belongs to
  double start_time_s = 0;                        // time of the first sample of the record
  std::size_t size() const { return time_s.size(); }
};

struct Gap {
  double from_s, to_s;  // times of the last sample before and the first sample after the gap
};

struct AveragingReport {
  std::vector<Gap> gaps;
  double sample_interval_s = 0;     // Δ, the median time step
  std::size_t dropped_windows = 0;  // windows with some samples but too few valid ones
  bool bursts = false;              // each gap-free run averaged as one window
  double median_run_s = 0;          // median length of the gap-free runs
  double median_spacing_s = 0;      // with bursts: median time between burst starts
};

// One window at a time. Feed samples in increasing time with add(), then call
// finish() once to close the last window and take the series.
class WindowAverager {
 public:
  // sample_interval_s is Δ. Throws InputError if the options are invalid or
  // the window is shorter than Δ. With whole_runs, every gap-free run is one
  // window (bursty records).
  WindowAverager(const AveragingOptions& options, double sample_interval_s, bool has_temp2,
                 bool whole_runs = false, std::vector<std::string> extra_names = {});

  // temp2_c is ignored when has_temp2 is false; extra holds this sample's
  // value of each extra column, in the order of extra_names.
  void add(double time_s, double temp_c, double gyro_dph, double temp2_c, bool valid,
           std::span<const double> extra = {});
  AveragedSeries finish();

  // After finish() it also holds the median run and, with whole runs, the
  // median spacing of their starts (and the series' window_s is the median run).
  const AveragingReport& report() const { return report_; }
  // The windows closed so far (a window closes when a sample beyond it, or
  // after a gap, arrives; the last one at finish()).
  const AveragedSeries& closed() const { return series_; }
  double record_s() const { return started_ ? last_time_s_ - series_.start_time_s : 0.0; }
  double longest_run_s() const { return longest_run_s_; }

 private:
  void close_window();
  void start_window(double time_s);

  AveragingOptions options_;
  double min_valid_samples_;  // min_fill · W/Δ
  bool has_temp2_;
  bool whole_runs_;
  std::vector<std::string> extra_names_;
  std::vector<double> sum_extra_;
  EdgeRate temp_edge_, temp2_edge_;
  std::vector<EdgeRate> extra_edges_;
  AveragedSeries series_;
  AveragingReport report_;

  bool started_ = false;
  double last_time_s_ = 0, run_start_s_ = 0, window_end_s_ = 0, longest_run_s_ = 0;
  std::size_t run_ = 0;
  // The current window: sums of the valid samples (time relative to the run start).
  std::size_t window_samples_ = 0, window_valid_ = 0;
  double sum_time_s_ = 0, sum_temp_c_ = 0, sum_gyro_dph_ = 0, sum_temp2_c_ = 0;
  // Within-window scatter, on gyro values less the window's first valid one
  // (so that the sums keep their digits): Σu, Σu², Σu_k·u_{k−1} and Σu_k,
  // Σu_{k−1} over consecutive valid pairs.
  double first_gyro_ = 0, sum_u_ = 0, sum_u2_ = 0, sum_lag_ = 0, sum_lag_now_ = 0, sum_lag_prev_ = 0;
  double previous_u_ = 0;
  bool previous_valid_ = false;
  std::size_t lag_pairs_ = 0;
};

// Rule 1: a time step of step_s is a gap.
bool is_gap(double step_s, double sample_interval_s, const AveragingOptions& options);

// Throws InputError naming `file` if `series` (from `averager`) holds no
// window, saying how long the record and its longest gap-free run are and what
// the window is.
void check_windows_survive(const std::string& file, const AveragedSeries& series,
                           const WindowAverager& averager, const AveragingOptions& options);

// The median time step of the record, s (Δ above). Needs at least 2 samples.
double median_sample_interval_s(const std::vector<double>& time_s);

// Bursts: more than one gap-free run, and the median run (first to last
// sample, plus Δ) shorter than the window.
bool in_bursts(const std::vector<double>& time_s, double sample_interval_s, const AveragingOptions& options);

// The gap-free runs of a record by rule 1: [first, last] sample indices.
std::vector<std::pair<std::size_t, std::size_t>> gap_free_runs(const std::vector<double>& time_s,
                                                               double sample_interval_s,
                                                               const AveragingOptions& options);

// Averages m (samples with valid[k] = 0 excluded; valid.size() == m.size()).
// Throws InputError naming m.file if no window survives, saying how long the
// record and its longest gap-free run are and what the window is.
AveragedSeries average_windows(const Measurement& m, const std::vector<unsigned char>& valid,
                               const AveragingOptions& options, AveragingReport* report = nullptr);

}  // namespace gyrotherm::fit
