#include "fit/record_support.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace gyrotherm::fit {

RecordSupport record_support(const PreparedData& data, const std::vector<const Term*>& terms) {
  RecordSupport s;
  s.flags.assign(terms.size(), "");
  const std::vector<double>& T = data.series.temp_c;
  const std::vector<double>& t = data.series.time_s;
  if (T.empty()) return s;
  const auto [lo, hi] = std::minmax_element(T.begin(), T.end());
  s.temp_min_c = *lo;
  s.temp_max_c = *hi;
  const double range = s.temp_max_c - s.temp_min_c;
  s.level_width_c = std::max(0.5, range / 40.0);
  std::map<long, int> bins;
  for (double v : T) ++bins[static_cast<long>(std::floor((v - s.temp_min_c) / s.level_width_c))];
  const int needed = std::max(2, static_cast<int>(std::ceil(0.03 * static_cast<double>(T.size()))));
  for (const auto& [bin, count] : bins) s.temperature_levels += count >= needed;
  // Spearman's rank correlation: any monotone warm-up or cool-down is 1.
  auto ranks = [](const std::vector<double>& v) {
    std::vector<std::size_t> order(v.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i;
      while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
      for (std::size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * static_cast<double>(i + j);  // ties share
      i = j + 1;
    }
    return r;
  };
  const std::vector<double> rt = ranks(t), rT = ranks(T);
  const double mean = 0.5 * static_cast<double>(T.size() - 1);
  double stt = 0, sTT = 0, stT = 0;
  for (std::size_t i = 0; i < T.size(); ++i) {
    stt += (rt[i] - mean) * (rt[i] - mean);
    sTT += (rT[i] - mean) * (rT[i] - mean);
    stT += (rt[i] - mean) * (rT[i] - mean);
  }
  s.temp_time_correlation = stt > 0 && sTT > 0 ? stT / std::sqrt(stt * sTT) : 0.0;

  for (std::size_t j = 0; j < terms.size(); ++j) {
    const effects::Family family = terms[j]->family;
    if (family != effects::Family::temperature_power && family != effects::Family::temperature_state)
      continue;
    std::vector<std::string> why;
    if (range < kNarrowRangeC)
      why.push_back(fmt::format("the record spans only {:.2g} °C", range));
    if (s.temperature_levels < kMinTemperatureLevels)
      why.push_back(fmt::format("it rests on {} temperature level{}", s.temperature_levels,
                                s.temperature_levels == 1 ? "" : "s"));
    if (std::abs(s.temp_time_correlation) > kTimeLockedCorrelation)
      why.push_back(fmt::format("temperature follows time (r = {:.2f}): a drift would be read as "
                                "temperature",
                                s.temp_time_correlation));
    std::string text;
    for (const std::string& w : why) text += (text.empty() ? "" : "; ") + w;
    s.flags[j] = text;
  }
  return s;
}

std::string describe_support(const RecordSupport& s) {
  return fmt::format("temperature {:.1f}..{:.1f} °C at {} level{} (bins of {:.2g} °C), r(T, t) = {:.2f}",
                     s.temp_min_c, s.temp_max_c, s.temperature_levels,
                     s.temperature_levels == 1 ? "" : "s", s.level_width_c, s.temp_time_correlation);
}

}  // namespace gyrotherm::fit
