#pragma once
// What a record can tell a model: the temperature range it covers, how many
// distinct temperature levels it dwells at, and how closely temperature
// follows time. A coefficient whose information comes from fewer than three
// levels, or from a range too narrow for its term, or from a temperature that
// moves with time (a drift would be read as temperature), is flagged, so
// that `fit` says plainly where the record cannot support its number.

#include <string>
#include <string_view>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/model/terms.h"

namespace gyrotherm::fit {

// Why a term is flagged: the first three leave a temperature model
// unsupported between or beyond what was measured (export refuses them); the
// last makes it uncertain what the coefficient means.
enum class SupportReason : int { narrow_range, few_levels, gap, time_locked };
inline constexpr int kSupportReasons = 4;
std::string_view to_string(SupportReason r);  // "narrow_range", "few_levels", "gap", "time_locked"
// Where the model is unsupported at some temperature inside or at its range.
inline bool limits_range(SupportReason r) { return r != SupportReason::time_locked; }

struct RecordSupport {
  double temp_min_c = 0, temp_max_c = 0;  // of the window means
  int temperature_levels = 0;  // exp(entropy) of the windows' share per bin of width level_width_c, rounded
  double level_width_c = 0;
  double temp_time_correlation = 0;  // Spearman's rank r of the window means' temperature and time
  // The widest temperature interval inside the range with no window mean in
  // it (°C, from..to): between two plateaus, a model is a guess.
  double gap_from_c = 0, gap_to_c = 0;
  std::vector<std::string> flags;    // per term: why the record cannot support it ("" if it can)
  std::vector<std::vector<SupportReason>> reasons;  // per term: the same as data
};

// Below these the flags are raised.
inline constexpr int kMinTemperatureLevels = 3;
inline constexpr double kNarrowRangeC = 2.0;
inline constexpr double kTimeLockedCorrelation = 0.95;
// A gap with no data wider than this share of the range.
inline constexpr double kGapShareOfRange = 0.25;

RecordSupport record_support(const PreparedData& data, const std::vector<const Term*>& terms);

// "temperature -40.0..60.0 °C at 3 levels; r(T, t) = 0.12"
std::string describe_support(const RecordSupport& support);

}  // namespace gyrotherm::fit
