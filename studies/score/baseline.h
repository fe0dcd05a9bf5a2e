#pragma once
// The baseline check of `score --baseline B.json`.
//
// An engine is worse than a saved scoreboard in a metric when the two 95 %
// intervals (studies/score/statistics.h) do not overlap in the worse direction
// (current low > baseline high for a cost, current high < baseline low for a
// benefit). Two non-overlapping 95 % intervals correspond to a test at about
// the 0.5 % level, so Monte Carlo noise alone rarely trips it, while a real
// loss (an engine that stops reaching the target, needs twice the
// evaluations, or loses accuracy) does. Gaps at or below ε count as equal
// (every one of them is "at the optimum"). Times are not checked: they belong
// to the machine.

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "studies/score/campaign.h"

namespace gyrotherm::studies {

// A saved scoreboard (`score --json`) as the baseline check needs it: per
// engine, each checked metric's value and 95 % interval.
struct BaselineMetric {
  double value = 0.0;
  Range ci;
};
struct Baseline {
  std::string file;
  std::string scenario, model;
  double target_relative = 0.0;
  std::size_t trials = 0;
  std::map<std::string, std::string> file_sha256;
  std::map<std::string, std::map<std::string, BaselineMetric>> engines;  // engine → metric → value
};
// Throws InputError naming the file and the field for a missing or malformed file.
Baseline load_baseline(const std::filesystem::path& file);
Baseline parse_baseline(std::string_view json, const std::string& where);

// The checked metrics of one engine, by the names of the JSON fields:
// success_rate, evals_to_target_median, gap_median, ratio_median and
// coefficient_error_median.<term>.
std::map<std::string, BaselineMetric> checked_metrics(const Scoreboard& board, const EngineScore& e);

// Where an engine is worse than the baseline beyond Monte Carlo noise;
// regression_text words it (one line with both values and intervals).
struct Regression {
  std::string engine;
  std::string metric;   // e.g. "success_rate", "coefficient_error_median.T"
  BaselineMetric now, baseline;
  bool higher_is_worse = true;  // a cost (above the baseline) or a benefit (below it)
};
std::string regression_text(const Regression& r);

// What the check could not compare; baseline_note_text words it.
struct BaselineNote {
  enum class Kind {
    file_changed,    // an input file's SHA-256 differs from the baseline's (`name`: the file's role)
    engine_missing,  // the baseline has no such engine (`name`: the engine)
    metric_missing   // the baseline has no such metric for the engine (`name`, `metric`)
  } kind = Kind::engine_missing;
  std::string name, metric;
};
std::string baseline_note_text(const BaselineNote& note);

struct BaselineComparison {
  std::vector<Regression> regressions;
  std::vector<BaselineNote> notes;
  bool passed() const { return regressions.empty(); }
};
// The rule of the header comment. Throws InputError if the baseline was made
// for another model or target (its numbers would not be comparable).
BaselineComparison compare_to_baseline(const Scoreboard& current, const Baseline& baseline);

}  // namespace gyrotherm::studies
