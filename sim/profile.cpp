#include "sim/profile.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace gyrotherm::sim {

const char* to_string(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::hold: return "hold";
    case SegmentKind::ramp: return "ramp";
    case SegmentKind::free: return "free";
  }
  return "?";
}

Profile::Profile(double start_c, std::vector<Segment> segments)
    : start_c_(start_c), segments_(std::move(segments)) {
  double t = 0.0;
  double sp = start_c_;
  for (Segment& s : segments_) {
    from_c_.push_back(sp);
    switch (s.kind) {
      case SegmentKind::hold:
        sp = s.temp_c;
        break;
      case SegmentKind::ramp:
        assert(s.rate_c_per_min > 0.0);
        s.duration_s = std::abs(s.temp_c - sp) / s.rate_c_per_min * 60.0;
        sp = s.temp_c;
        break;
      case SegmentKind::free:
        break;
    }
    t += s.duration_s;
    ends_s_.push_back(t);
  }
}

std::size_t Profile::segment_at(double t_s) const {
  assert(!segments_.empty());
  // First segment whose end lies after t; a time on a breakpoint belongs to the
  // segment that starts there.
  const auto it = std::upper_bound(ends_s_.begin(), ends_s_.end(), t_s);
  if (it == ends_s_.end()) return segments_.size() - 1;
  return static_cast<std::size_t>(it - ends_s_.begin());
}

SetPoint Profile::at(double t_s) const {
  if (segments_.empty()) return {start_c_, 0.0, true};
  const std::size_t i = segment_at(t_s);
  const Segment& s = segments_[i];
  switch (s.kind) {
    case SegmentKind::hold:
      return {s.temp_c, 0.0, true};
    case SegmentKind::ramp: {
      if (s.duration_s <= 0.0) return {s.temp_c, 0.0, true};
      const double from = from_c_[i];
      const double fraction = std::clamp((t_s - segment_start_s(i)) / s.duration_s, 0.0, 1.0);
      const double sign = s.temp_c >= from ? 1.0 : -1.0;
      return {from + (s.temp_c - from) * fraction, sign * s.rate_c_per_min / 60.0, true};
    }
    case SegmentKind::free:
      return {from_c_[i], 0.0, false};
  }
  return {start_c_, 0.0, true};
}

}  // namespace gyrotherm::sim
