#include "app/progress.h"

#include <fmt/core.h>
#include <unistd.h>

namespace gyrotherm::app {

std::function<void(const std::string&, double)> step_progress() {
  const bool tty = ::isatty(2) != 0;
  return [tty](const std::string& step, double f) {
    if (tty)
      fmt::print(stderr, "\r[{:3.0f}%] {:<50}", 100.0 * f, step);
    else
      fmt::print(stderr, "[{:3.0f}%] {}\n", 100.0 * f, step);
    if (tty && f >= 1.0) fmt::print(stderr, "\n");
  };
}

TrialProgress::TrialProgress(std::string label) : label_(std::move(label)), tty_(::isatty(2) != 0) {}

void TrialProgress::on_trial_done(std::size_t done, std::size_t total) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const double eta = elapsed / static_cast<double>(done) * static_cast<double>(total - done);
  if (tty_) {
    if (done != total && elapsed - last_draw_s_ < 0.1) return;  // at most ten redraws a second
    last_draw_s_ = elapsed;
    constexpr int kWidth = 30;
    const auto filled = static_cast<int>(kWidth * static_cast<double>(done) / static_cast<double>(total));
    fmt::print(stderr, "\r{} [{}{}] {}/{} trials, {:.1f} s, ETA {:.1f} s   ", label_, std::string(filled, '#'),
               std::string(kWidth - filled, '.'), done, total, elapsed, eta);
    if (done == total) fmt::print(stderr, "\n");
    return;
  }
  const std::size_t decile = 10 * done / total;
  if (decile == last_decile_ && done != total) return;
  last_decile_ = decile;
  fmt::print(stderr, "{}: {}/{} trials, {:.1f} s, ETA {:.1f} s\n", label_, done, total, elapsed, eta);
}

}  // namespace gyrotherm::app
