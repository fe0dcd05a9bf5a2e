// Step 2 of diagnose() (studies/diagnose/diagnosis.h): where the model fails,
// by segments of the record's own temperature history and by temperature band.
#include <algorithm>
#include <cmath>
#include <limits>

#include "studies/diagnose/diagnosis_steps.h"

namespace gyrotherm::studies {

const char* to_string(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::turn_on: return "turn-on";
    case SegmentKind::heating: return "heating";
    case SegmentKind::cooling: return "cooling";
    case SegmentKind::soak: return "soak";
    case SegmentKind::band: return "band";
  }
  return "";
}

std::vector<std::size_t> Diagnosis::worst_segments() const {
  std::vector<std::size_t> idx(segments.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return segments[a].ratio_to_floor > segments[b].ratio_to_floor;
  });
  return idx;
}

std::vector<SegmentReport> segment_rms(const Diagnosis& d, const std::vector<double>& residual) {
  std::vector<SegmentReport> out = d.segments;
  std::vector<double> ss(out.size(), 0.0);
  for (std::size_t p = 0; p < residual.size(); ++p) ss[d.window_segment[p]] += residual[p] * residual[p];
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].rms_dph = std::sqrt(ss[i] / static_cast<double>(out[i].windows));
    out[i].ratio_to_floor = out[i].rms_dph / d.noise_floor_dph;
  }
  return out;
}

namespace diagnosis_steps {

void locate_failures(Diagnosis& d, const fit::PreparedData& data) {
  const fit::AveragedSeries& s = data.series;
  const std::size_t l = s.size();
  // Segments from the temperature record.
  const std::vector<double>& rate = data.derived.rate_c_per_s;
  double max_rate = 0.0;
  for (double r : rate) max_rate = std::max(max_rate, std::abs(r));
  const double threshold = std::max(2e-4, 0.05 * max_rate);
  std::vector<SegmentKind> kind(l);
  for (std::size_t p = 0; p < l; ++p) {
    if (s.time_s[p] - s.start_time_s < 1800.0)
      kind[p] = SegmentKind::turn_on;
    else if (rate[p] > threshold)
      kind[p] = SegmentKind::heating;
    else if (rate[p] < -threshold)
      kind[p] = SegmentKind::cooling;
    else
      kind[p] = SegmentKind::soak;
  }
  // Runs shorter than 3 windows take the kind of the run before them.
  for (std::size_t p = 0; p < l;) {
    std::size_t q = p;
    while (q < l && kind[q] == kind[p]) ++q;
    if (q - p < 3 && p > 0 && kind[p] != SegmentKind::turn_on)
      for (std::size_t i = p; i < q; ++i) kind[i] = kind[p - 1];
    p = q;
  }
  d.window_segment.resize(l);
  for (std::size_t p = 0; p < l; ++p) {
    // A segment ends where the kind changes or the record stops for longer
    // than the derivatives' span (a bursty logger's bursts stay together).
    const bool new_segment = p == 0 || kind[p] != kind[p - 1] ||
                             (s.run[p] != s.run[p - 1] &&
                              s.time_s[p] - s.time_s[p - 1] > data.derivative_span_s);
    if (new_segment) {
      SegmentReport seg;
      seg.kind = kind[p];
      seg.start_s = s.time_s[p] - s.start_time_s;
      seg.temp_min_c = seg.temp_max_c = s.temp_c[p];
      d.segments.push_back(seg);
    }
    SegmentReport& seg = d.segments.back();
    seg.end_s = s.time_s[p] - s.start_time_s;
    seg.temp_min_c = std::min(seg.temp_min_c, s.temp_c[p]);
    seg.temp_max_c = std::max(seg.temp_max_c, s.temp_c[p]);
    seg.windows += 1;
    d.window_segment[p] = d.segments.size() - 1;
  }
  d.segments = segment_rms(d, d.residual_dph());

  // Temperature bands: four of equal width.
  const auto [tlo, thi] = std::minmax_element(s.temp_c.begin(), s.temp_c.end());
  const double width = std::max((*thi - *tlo) / 4.0, 1e-9);
  d.bands.resize(4);
  std::vector<double> band_ss(4, 0.0);
  for (int b = 0; b < 4; ++b) {
    d.bands[static_cast<std::size_t>(b)].kind = SegmentKind::band;
    d.bands[static_cast<std::size_t>(b)].temp_min_c = *tlo + b * width;
    d.bands[static_cast<std::size_t>(b)].temp_max_c = *tlo + (b + 1) * width;
    d.bands[static_cast<std::size_t>(b)].start_s = std::numeric_limits<double>::infinity();
    d.bands[static_cast<std::size_t>(b)].end_s = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t p = 0; p < l; ++p) {
    const auto b = static_cast<std::size_t>(std::min(3.0, std::floor((s.temp_c[p] - *tlo) / width)));
    d.bands[b].windows += 1;
    band_ss[b] += d.residual_dph()[p] * d.residual_dph()[p];
    d.bands[b].start_s = std::min(d.bands[b].start_s, s.time_s[p] - s.start_time_s);
    d.bands[b].end_s = std::max(d.bands[b].end_s, s.time_s[p] - s.start_time_s);
  }
  for (std::size_t b = 0; b < 4; ++b) {
    if (d.bands[b].windows == 0) continue;
    d.bands[b].rms_dph = std::sqrt(band_ss[b] / static_cast<double>(d.bands[b].windows));
    d.bands[b].ratio_to_floor = d.bands[b].rms_dph / d.noise_floor_dph;
  }
  std::erase_if(d.bands, [](const SegmentReport& b) { return b.windows == 0; });
}

}  // namespace diagnosis_steps
}  // namespace gyrotherm::studies
