#pragma once
// The real-time compensator (`compensate --causal`, and what `export --format
// c` writes in C): each sample gets the model's bias from what came before
// it, nothing after.
//
// Per sample, in time order:
//   1. The glitch rule, trailing: the sample is judged against the samples of
//      the last W_o seconds (itself included), Hampel's test with the local
//      MAD and the fit's global floor s_floor (fit/data/hampel.h; the offline
//      rule centres its window and so looks W_o/2 ahead).
//   2. The windows of the fit (fit/data/averaging.h) with the fit's sample
//      interval Δ and burst mode, fed one sample at a time; a window closes
//      when a sample beyond it, or after a gap, arrives.
//   3. When a window closes: its backward derivatives and every term of the
//      model, the model's bias B at that window. A closed window's row reads
//      that window and the two before it (a backward rate the one before, the
//      second derivative and a rate under a sensor time constant the two
//      before), and a term with memory (lag) its own value at the window
//      before, carried (Effect::next): the same numbers as the terms over the
//      whole history, in constant time per window.
//   4. The sample's bias is B of the latest closed window; before the first
//      one closes, B of the sample itself taken as a window (its temperature,
//      rates 0).
// Δ, the burst mode and s_floor are the fit's (the record it was fitted on),
// not re-estimated from the record being compensated, so the compensator is
// the same on any record and needs no look at the whole of it.

#include <memory>
#include <optional>
#include <utility>
#include <span>
#include <string>
#include <vector>

#include "fit/data/averaging.h"
#include "fit/data/hampel.h"
#include "fit/fit_file.h"

namespace gyrotherm::fit {

struct CausalSettings {
  double sample_interval_s = 1.0;  // Δ
  bool bursts = false;             // every gap-free run one window
  double outlier_floor_dph = 0.0;  // s_floor
  // The fit's temperature range (°C) the temperature terms are held within
  // (fit/model/terms.h design_matrix_held), or none: evaluated anywhere.
  std::optional<std::pair<double, double>> hold_c;
};

class CausalCompensator {
 public:
  // extra_names: the log columns the model's column terms read, in the order
  // update() is given their values.
  CausalCompensator(const SavedFit& fit, const CausalSettings& settings, std::vector<std::string> extra_names = {});

  // The model's bias (°/h) for this sample; *glitch says whether the glitch
  // rule rejected it (it then enters no window).
  double update(double time_s, double temp_c, double temp2_c, double gyro_dph, std::span<const double> extra,
                bool* glitch);

  std::size_t closed_windows() const { return averager_.closed().size(); }
  // The bias at each closed window, in order.
  const std::vector<double>& window_bias_dph() const { return window_bias_; }

 private:
  // B at the last of `windows` (the latest closed ones, or a sample as a
  // window of its own); `carry`: the terms with memory continue from state_,
  // which then holds their values at this window.
  double bias_of(const AveragedSeries& windows, bool carry);

  const SavedFit& fit_;
  CausalSettings settings_;
  std::vector<std::string> extra_names_;
  WindowAverager averager_;
  TrailingHampel glitches_;  // the glitch rule's trailing window
  std::vector<double> window_bias_;
  std::vector<double> state_;  // each term with memory: its regressor at the latest closed window
  bool started_ = false;
  double start_time_s_ = 0.0;
};

}  // namespace gyrotherm::fit
