#include "studies/plan/profiles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gyrotherm::studies::plan {

namespace {

sim::Segment ramp(double to_c, double rate_c_per_min) { return {sim::SegmentKind::ramp, to_c, rate_c_per_min, 0.0, 0}; }
sim::Segment hold(double at_c, double duration_s) { return {sim::SegmentKind::hold, at_c, 0.0, duration_s, 0}; }

constexpr int kSineSteps = 24;  // ramps per period

}  // namespace

double ChamberProfile::duration_s() const {
  return sim::Profile(start_c, segments).duration_s();
}

ChamberProfile profile_of(const LegProfile& legs) {
  ChamberProfile p{legs.start_c, {}};
  std::vector<sim::Segment>& out = p.segments;
  double at = legs.start_c;
  for (std::size_t i = 0; i < legs.targets_c.size(); ++i) {
    if (legs.targets_c[i] != at) out.push_back(ramp(legs.targets_c[i], legs.rate_c_per_min));
    at = legs.targets_c[i];
    if (i < legs.soaks_s.size() && legs.soaks_s[i] > 0.0) out.push_back(hold(at, legs.soaks_s[i]));
  }
  return p;
}

double duration_of(const LegProfile& legs) {
  double d = 0.0, at = legs.start_c;
  for (std::size_t i = 0; i < legs.targets_c.size(); ++i) {
    d += std::abs(legs.targets_c[i] - at) / legs.rate_c_per_min * 60.0;
    at = legs.targets_c[i];
    if (i < legs.soaks_s.size()) d += legs.soaks_s[i];
  }
  return d;
}

double shortest_sine_period_s(const RigLimits& limits) {
  const double amplitude = 0.5 * (limits.high_c - limits.low_c);
  return 2.0 * std::numbers::pi * amplitude / (limits.max_rate_c_per_min / 60.0);
}

ChamberProfile sine_profile(const RigLimits& limits, double period_s, int periods) {
  const double mid = 0.5 * (limits.low_c + limits.high_c), amplitude = 0.5 * (limits.high_c - limits.low_c);
  ChamberProfile p{limits.start_c, {}};
  std::vector<sim::Segment>& out = p.segments;
  if (limits.start_c != mid) out.push_back(ramp(mid, limits.max_rate_c_per_min));
  const double step_s = period_s / kSineSteps;
  double previous = mid;
  for (int k = 1; k <= periods * kSineSteps; ++k) {
    const double next = mid + amplitude * std::sin(2.0 * std::numbers::pi * k / kSineSteps);
    const double change = std::abs(next - previous);
    // A ramp's rate gives its length; a step with no change (none here) would be a hold.
    if (change < 1e-9) {
      out.push_back(hold(next, step_s));
    } else {
      out.push_back(ramp(next, change / step_s * 60.0));
    }
    previous = next;
  }
  return p;
}

ChamberProfile Recipe::profile(double x) const {
  const RigLimits& r = limits;
  LegProfile legs;
  legs.start_c = start_c;
  legs.rate_c_per_min = r.max_rate_c_per_min;
  switch (kind) {
    case Kind::warmup:
      legs.targets_c = {r.high_c};
      legs.soaks_s = {x};
      break;
    case Kind::staircase:
      for (int k = 0; k <= 4; ++k) {
        legs.targets_c.push_back(r.low_c + (r.high_c - r.low_c) * k / 4.0);
        legs.soaks_s.push_back(x);
      }
      break;
    case Kind::triangle:
      legs.rate_c_per_min = x;
      legs.targets_c.push_back(r.low_c);
      for (int c = 0; c < cycles; ++c) {
        legs.targets_c.push_back(r.high_c);
        legs.targets_c.push_back(r.low_c);
      }
      legs.soaks_s.assign(legs.targets_c.size(), 0.0);
      break;
    case Kind::sine:
      return sine_profile(r, x, cycles);
    case Kind::soak_cycle:
      legs.targets_c = {r.start_c, r.high_c, r.low_c, r.high_c};
      legs.soaks_s.assign(4, x);
      break;
  }
  return profile_of(legs);
}

std::vector<Recipe> standard_recipes(const RigLimits& limits) {
  const double longest = limits.longest_s;
  const double soak = std::max(limits.min_soak_s, 60.0);
  const double span = limits.high_c - limits.low_c;
  const double mid = 0.5 * (limits.low_c + limits.high_c);
  // Seconds of ramping at the rate limit over `degrees`.
  auto ramping = [&](double degrees) { return degrees / limits.max_rate_c_per_min * 60.0; };
  // The longest soak x when `count` soaks share the test with `ramps_s` of ramps
  // (at least the shortest soak: a test that cannot fit is then simply too long).
  auto soak_range = [&](double ramps_s, int count) { return std::max(soak, (longest - ramps_s) / count); };
  std::vector<Recipe> out;
  Recipe warmup{"warm-up from cold",
                "cold-soaked unpowered, switched on and warmed to the high end (PX4, ArduPilot)",
                soak, soak_range(ramping(span), 1), false, limits.low_c};
  warmup.kind = Recipe::Kind::warmup;
  out.push_back(warmup);
  Recipe stairs{"soak staircase", "five levels low to high, a soak at each", soak,
                soak_range(ramping(std::abs(limits.start_c - limits.low_c) + span), 5), false, limits.start_c};
  stairs.kind = Recipe::Kind::staircase;
  out.push_back(stairs);
  for (int cycles : {1, 2}) {
    const double path_c = std::abs(limits.start_c - limits.low_c) + 2.0 * cycles * span;
    Recipe tri{cycles == 1 ? "triangle, one cycle" : "triangle, two cycles",
               "continuous ramps low-high-low (Niu et al., Sensors 13(9):12192, 2013)",
               std::min(limits.max_rate_c_per_min, path_c / (longest / 60.0)), limits.max_rate_c_per_min, true,
               limits.start_c};
    tri.kind = Recipe::Kind::triangle;
    tri.cycles = cycles;
    out.push_back(tri);
  }
  const double shortest_period = shortest_sine_period_s(limits);
  Recipe sine{"sine, two periods", "the set point a sine over the whole range", shortest_period,
              std::max(shortest_period, (longest - ramping(std::abs(limits.start_c - mid))) / 2.0), false,
              limits.start_c};
  sine.kind = Recipe::Kind::sine;
  sine.cycles = 2;
  out.push_back(sine);
  Recipe cycle{"soak-and-ramp cycle", "soaks at the start and at high, low, high (the paper's training test)",
               soak, soak_range(ramping(std::abs(limits.start_c - limits.high_c) + 2.0 * span), 4), false,
               limits.start_c};
  cycle.kind = Recipe::Kind::soak_cycle;
  out.push_back(cycle);
  for (Recipe& r : out) r.limits = limits;
  return out;
}

}  // namespace gyrotherm::studies::plan
