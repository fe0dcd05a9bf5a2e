#include "fit/record_support.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace gyrotherm::fit {

RecordSupport record_support(const PreparedData& data, const std::vector<const Term*>& terms) {
  RecordSupport s;
  s.flags.assign(terms.size(), "");
  s.reasons.assign(terms.size(), {});
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
  // The effective number of levels: the perplexity exp(H) of the windows'
  // share per bin (a Hill number), rounded: two equal plateaus are 2, a
  // plateau with a tenth of the windows elsewhere less than 2, and a ramp
  // as many as the bins it crosses (a count of bins above a share would
  // call a steady ramp no level at all).
  double entropy = 0.0;
  for (const auto& [bin, count] : bins) {
    const double p = static_cast<double>(count) / static_cast<double>(T.size());
    entropy -= p * std::log(p);
  }
  s.temperature_levels = static_cast<int>(std::lround(std::exp(entropy)));
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
  {
    std::vector<double> sorted = T;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i)
      if (sorted[i] - sorted[i - 1] > s.gap_to_c - s.gap_from_c) {
        s.gap_from_c = sorted[i - 1];
        s.gap_to_c = sorted[i];
      }
  }
  const double gap = s.gap_to_c - s.gap_from_c;

  for (std::size_t j = 0; j < terms.size(); ++j) {
    if (!fit::reads_temperature_level(terms[j])) continue;
    std::vector<std::string> why;
    std::vector<SupportReason>& reasons = s.reasons[j];
    if (range < kNarrowRangeC) {
      reasons.push_back(SupportReason::narrow_range);
      why.push_back(fmt::format("the record spans only {:.2g} °C", range));
    }
    if (s.temperature_levels < kMinTemperatureLevels) {
      reasons.push_back(SupportReason::few_levels);
      why.push_back(fmt::format("it rests on {} temperature level{}", s.temperature_levels,
                                s.temperature_levels == 1 ? "" : "s"));
    }
    if (range >= kNarrowRangeC && gap > kGapShareOfRange * range) {
      reasons.push_back(SupportReason::gap);
      why.push_back(fmt::format("no data between {:.1f} and {:.1f} °C ({:.0f} % of the range): the model there is a "
                                "guess",
                                s.gap_from_c, s.gap_to_c, 100.0 * gap / range));
    }
    if (std::abs(s.temp_time_correlation) > kTimeLockedCorrelation) {
      reasons.push_back(SupportReason::time_locked);
      why.push_back(fmt::format("temperature follows time (r = {:.2f}): a drift would be read as "
                                "temperature",
                                s.temp_time_correlation));
    }
    std::string text;
    for (const std::string& w : why) text += (text.empty() ? "" : "; ") + w;
    s.flags[j] = text;
  }
  return s;
}

std::string_view to_string(SupportReason r) {
  static constexpr std::string_view kNames[kSupportReasons] = {"narrow_range", "few_levels", "gap", "time_locked"};
  const auto i = static_cast<std::size_t>(r);
  return i < std::size(kNames) ? kNames[i] : "?";
}

std::string describe_support(const RecordSupport& s) {
  return fmt::format("temperature {:.1f}..{:.1f} °C at {} level{} (bins of {:.2g} °C), r(T, t) = {:.2f}",
                     s.temp_min_c, s.temp_max_c, s.temperature_levels,
                     s.temperature_levels == 1 ? "" : "s", s.level_width_c, s.temp_time_correlation);
}

}  // namespace gyrotherm::fit
