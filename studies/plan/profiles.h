#pragma once
// The chamber profiles `gyrotherm plan` compares, as sequences of ramps and
// soaks (sim/profile.h) within the rig's limits:
//
//   legs       from the start, ramp at `rate` to each target in turn and hold
//              there for its soak (0: turn at once). The planned profile is
//              such a sequence alternating between the range's ends, its
//              soaks chosen by the search (studies/plan/search.h); the
//              standard recipes below are fixed shapes of it.
//   sine       the set point mid + A·sin(2πt/P) over whole periods, as ramps
//              of P/24 each (a chamber programmer's segments), its amplitude
//              the range's half and P no shorter than the rate allows.
//
// The standard recipes, each with one length parameter x (a longer x, a
// longer test):
//   warm-up from cold   the unit soaked at the range's low end (cold-soaked
//                       unpowered, as PX4's and ArduPilot's procedures ask;
//                       that soak is not counted), switched on, the chamber
//                       ramped to the high end and held there for x;
//   soak staircase      from the start down to the low end, then up in four
//                       equal steps to the high end, soaking x at each of
//                       the five levels;
//   triangle ×1, ×2     one or two full cycles low → high → low, continuous
//                       ramps at rate x (Niu et al., Sensors 13(9):12192,
//                       2013); slower ramps make a longer test;
//   sine                two periods of period x;
//   soak-and-ramp cycle the paper's training test (Yu et al. 2014): a soak x
//                       at the start, then high, low, high at the rate
//                       limit with a soak x at each.

#include <string>
#include <vector>

#include "sim/profile.h"

namespace gyrotherm::studies::plan {

// The rig's limits a profile must keep.
struct RigLimits {
  double low_c = -40.0, high_c = 60.0;  // the chamber set point's range (--range)
  double max_rate_c_per_min = 5.0;      // --max-rate
  double min_soak_s = 0.0;              // a soak lasts at least this (--min-soak)
  double start_c = 20.0;                // the unit soaked here and switched on at t = 0
  double longest_s = 72.0 * 3600.0;     // no test longer than this is considered (--longest)
};

// A profile as a test runs it: the unit soaked at start_c and switched on at
// t = 0, then the segments.
struct ChamberProfile {
  double start_c = 20.0;
  std::vector<sim::Segment> segments;
  double duration_s() const;
};

struct LegProfile {
  double start_c = 20.0;
  double rate_c_per_min = 5.0;
  std::vector<double> targets_c;
  std::vector<double> soaks_s;  // one per target
};
ChamberProfile profile_of(const LegProfile& legs);
double duration_of(const LegProfile& legs);

// Sine of period_s about the range's middle, `periods` of them, after a ramp
// from the start to the middle at the rate limit.
ChamberProfile sine_profile(const RigLimits& limits, double period_s, int periods);
// The shortest period the rate limit allows: 2π·A/rate.
double shortest_sine_period_s(const RigLimits& limits);

struct Recipe {
  std::string name;   // "warm-up from cold", ...
  std::string about;  // one line on where it comes from
  double x_min = 0, x_max = 0;  // the length parameter's range (x_max: the longest)
  bool x_is_rate = false;       // x is a ramp rate (°C/min): a larger x is a shorter test
  double start_c = 0;           // where the unit starts
  // The profile at x.
  ChamberProfile profile(double x) const;

  enum class Kind { warmup, staircase, triangle, sine, soak_cycle } kind = Kind::triangle;
  int cycles = 1;  // triangle: cycles; sine: periods
  RigLimits limits;
};

// The standard recipes at these limits, in the order the report lists them.
std::vector<Recipe> standard_recipes(const RigLimits& limits);

}  // namespace gyrotherm::studies::plan
