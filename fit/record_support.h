#pragma once
// What a record can tell a model: the temperature range it covers, how many
// distinct temperature levels it dwells at, and how closely temperature
// follows time. A coefficient whose information comes from fewer than three
// levels, or from a range too narrow for its term, or from a temperature that
// moves with time (a drift would be read as temperature), is flagged, so
// that `fit` says plainly where the record cannot support its number.

#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/model/terms.h"

namespace gyrotherm::fit {

struct RecordSupport {
  double temp_min_c = 0, temp_max_c = 0;  // of the window means
  int temperature_levels = 0;  // bins of width level_width_c holding ≥ 3 % of the windows (at least 2)
  double level_width_c = 0;
  double temp_time_correlation = 0;  // Spearman's rank r of the window means' temperature and time
  std::vector<std::string> flags;    // per term: why the record cannot support it ("" if it can)
};

// Below these the flags are raised.
inline constexpr int kMinTemperatureLevels = 3;
inline constexpr double kNarrowRangeC = 2.0;
inline constexpr double kTimeLockedCorrelation = 0.95;

RecordSupport record_support(const PreparedData& data, const std::vector<const Term*>& terms);

// "temperature -40.0..60.0 °C at 3 levels; r(T, t) = 0.12"
std::string describe_support(const RecordSupport& support);

}  // namespace gyrotherm::fit
