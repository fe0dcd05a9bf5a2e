#pragma once
// Progress on the terminal (stderr) for the long commands: a bar with an ETA
// when stderr is a terminal, a plain line every 10 % (or every step)
// otherwise, so that a log file stays readable.

#include <chrono>
#include <functional>
#include <string>

#include "studies/score/campaign.h"

namespace gyrotherm::app {

// reproduce's steps: (what, share done).
std::function<void(const std::string& step, double fraction)> step_progress();

// score's trials.
class TrialProgress final : public studies::ScoreObserver {
 public:
  explicit TrialProgress(std::string label);
  void on_trial_done(std::size_t done, std::size_t total) override;

 private:
  std::string label_;
  bool tty_;
  std::size_t last_decile_ = 0;
  double last_draw_s_ = -1.0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace gyrotherm::app
