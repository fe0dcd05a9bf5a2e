#pragma once
// A temperature profile: the chamber set point as a function of time, built
// from segments that run one after another.
//
//   hold  T, d    the set point steps to T (if it is not there) and stays d seconds
//   ramp  T, r    the set point moves linearly to T at r °C/min; lasts |T − T_prev|/r
//   free  d       the chamber is switched off for d seconds and drifts towards
//                 the room (the set point is kept only for a later ramp to start from)
//
// The set point is piecewise linear, so the thermal model's right-hand side is
// smooth inside a segment; the breakpoints are where the integrator stops and
// restarts.

#include <cstddef>
#include <string>
#include <vector>

namespace gyrotherm::sim {

enum class SegmentKind { hold, ramp, free };

const char* to_string(SegmentKind kind);

struct Segment {
  SegmentKind kind = SegmentKind::hold;
  double temp_c = 0.0;          // hold: temperature; ramp: target
  double rate_c_per_min = 0.0;  // ramp only, > 0
  double duration_s = 0.0;      // hold and free; ramps get theirs from the rate
  std::size_t source_line = 0;  // where the segment was defined, for messages (0: unknown)
};

struct SetPoint {
  double temp_c = 0.0;
  double rate_c_per_s = 0.0;  // d(set point)/dt
  bool chamber_on = true;
};

class Profile {
 public:
  // start_c: the set point before the first segment.
  Profile(double start_c, std::vector<Segment> segments);

  SetPoint at(double t_s) const;
  // Index of the segment that contains t (the last one for t ≥ the end).
  std::size_t segment_at(double t_s) const;

  double duration_s() const { return ends_s_.empty() ? 0.0 : ends_s_.back(); }
  double start_c() const { return start_c_; }
  const std::vector<Segment>& segments() const { return segments_; }
  double segment_start_s(std::size_t i) const { return i == 0 ? 0.0 : ends_s_[i - 1]; }
  double segment_end_s(std::size_t i) const { return ends_s_[i]; }
  // Set point at the start of segment i (where a ramp starts from).
  double segment_start_c(std::size_t i) const { return from_c_[i]; }

 private:
  double start_c_;
  std::vector<Segment> segments_;
  std::vector<double> ends_s_;   // end time of each segment
  std::vector<double> from_c_;   // set point at each segment's start
};

}  // namespace gyrotherm::sim
