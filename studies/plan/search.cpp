#include "studies/plan/search.h"

#include "sim/util/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace gyrotherm::studies::plan {

namespace {

constexpr int kScanSteps = 14;     // geometric grid of a length parameter
constexpr int kBisections = 6;     // then narrowed to (range)^(1/14/64)
constexpr int kLocalSteps = 6;     // a shape's move: the grid about the current scale ...
constexpr double kLocalReach = 4.0;  // ... from s/4 to 4s
constexpr int kPatternSweeps = 4;  // pattern-search sweeps over a shape

// A candidate is better than another: met before not met, then shorter when
// met, closer to the target when not.
bool better(const Candidate& a, const Candidate& b) {
  if (b.precision.se.empty()) return true;  // b: none yet
  if (a.met() != b.met()) return a.met();
  if (a.fits != b.fits) return a.fits;
  if (a.met()) return a.precision.duration_s < b.precision.duration_s;
  return a.shortfall < b.shortfall;
}

// Smallest x in [lo, hi] (geometric) whose profile meets the target, with
// `longer(x)` true when a larger x is a longer test.
template <class Make>
SearchOutcome scan(const DesignEvaluator& ev, const std::vector<double>& target, double longest_s, double lo,
                   double hi, bool larger_is_longer, const Make& make, int steps = kScanSteps) {
  SearchOutcome out;
  out.best.shortfall = std::numeric_limits<double>::infinity();
  if (!(hi > lo)) steps = 0;  // one length only
  auto at = [&](double x) {
    Candidate c = candidate_of(ev, make(x), target, longest_s);
    ++out.evaluations;
    if (better(c, out.best)) out.best = c;
    return c.met();
  };
  // Order the grid from the shortest test to the longest.
  auto point = [&](double f) {
    const double l = std::log(lo), h = std::log(hi);
    return std::exp(larger_is_longer ? l + f * (h - l) : h - f * (h - l));
  };
  double previous = -1.0;
  for (int k = 0; k <= steps; ++k) {
    const double f = steps == 0 ? 0.0 : static_cast<double>(k) / steps;
    if (!at(point(f))) {
      previous = f;
      continue;
    }
    if (previous >= 0.0) {
      double a = previous, b = f;  // a fails, b meets
      for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (a + b);
        (at(point(mid)) ? b : a) = mid;
      }
    }
    break;
  }
  out.met = out.best.met();
  return out;
}

// The planned family: `legs` legs, the low end first or not.
SearchOutcome plan_family(const DesignEvaluator& ev, const RigLimits& limits, const std::vector<double>& target,
                          int legs, bool low_first) {
  LegProfile base;
  base.start_c = limits.start_c;
  base.rate_c_per_min = limits.max_rate_c_per_min;
  for (int i = 0; i < legs; ++i) base.targets_c.push_back((i % 2 == 0) == low_first ? limits.low_c : limits.high_c);
  const double min_scale = std::max(limits.min_soak_s, 60.0);
  auto make = [&](const std::vector<double>& shape, double scale) {
    LegProfile p = base;
    for (double u : shape) p.soaks_s.push_back(u > 0.0 ? std::max(limits.min_soak_s, scale * u) : 0.0);
    return profile_of(p);
  };
  SearchOutcome total;
  total.best.shortfall = std::numeric_limits<double>::infinity();
  // The shortest scale of a shape: over the whole range, or about `around`
  // (the current shape's scale: a move changes one soak, not the test's length).
  auto shortest = [&](const std::vector<double>& shape, double around = 0.0) {
    const double ramps_s = duration_of(base);
    double sum = 0.0;
    for (double u : shape) sum += u;
    SearchOutcome o;
    if (sum == 0.0) {
      o = scan(ev, target, limits.longest_s, 1.0, 1.0, true, [&](double s) { return make(shape, s); });
    } else {
      const double hi = std::max(min_scale, (limits.longest_s - ramps_s) / sum);
      const double lo = std::min(min_scale, hi);
      if (around > 0.0)
        o = scan(ev, target, limits.longest_s, std::clamp(around / kLocalReach, lo, hi),
                 std::clamp(around * kLocalReach, lo, hi), true, [&](double s) { return make(shape, s); },
                 kLocalSteps);
      else
        o = scan(ev, target, limits.longest_s, lo, hi, true, [&](double s) { return make(shape, s); });
    }
    total.evaluations += o.evaluations;
    if (better(o.best, total.best)) total.best = o.best;
    return o;
  };
  // The scale s of a candidate made from `shape`: its longest soak over the shape's.
  auto scale_of = [&](const Candidate& c, const std::vector<double>& shape) {
    double longest_soak = 0.0, largest = 0.0;
    for (const sim::Segment& seg : c.profile.segments)
      if (seg.kind == sim::SegmentKind::hold) longest_soak = std::max(longest_soak, seg.duration_s);
    for (double u : shape) largest = std::max(largest, u);
    return largest > 0.0 && longest_soak > 0.0 ? longest_soak / largest : 0.0;
  };
  shortest(std::vector<double>(static_cast<std::size_t>(legs), 0.0));  // turning at once (kept in total)
  std::vector<double> shape(static_cast<std::size_t>(legs), 1.0);
  SearchOutcome current = shortest(shape);
  for (int sweep = 0; sweep < kPatternSweeps; ++sweep) {
    bool improved = false;
    std::vector<double> best_shape = shape;
    Candidate best = current.best;
    for (std::size_t i = 0; i < shape.size(); ++i) {
      for (double factor : {2.0, 0.5, 0.0}) {
        if (shape[i] == 0.0 && factor != 2.0) continue;
        std::vector<double> trial = shape;
        trial[i] = shape[i] == 0.0 ? 0.5 : shape[i] * factor;
        const SearchOutcome o = shortest(trial, scale_of(current.best, shape));
        if (better(o.best, best)) {
          best = o.best;
          best_shape = trial;
          improved = true;
        }
      }
    }
    if (!improved) break;
    shape = best_shape;
    current.best = best;
  }
  total.met = total.best.met();
  return total;
}

}  // namespace

Candidate candidate_of(const DesignEvaluator& evaluator, ChamberProfile profile, const std::vector<double>& target,
                       double longest_s) {
  Candidate c;
  c.profile = std::move(profile);
  c.precision = evaluator.precision(c.profile);
  c.shortfall = shortfall(c.precision, target);
  c.fits = c.precision.duration_s <= longest_s * (1.0 + 1e-9);
  return c;
}

double shortfall(const Precision& p, const std::vector<double>& target) {
  double worst = 0.0;
  for (std::size_t j = 0; j < target.size() && j < p.se.size(); ++j)
    if (std::isfinite(target[j])) {
      worst = std::max(worst, p.se[j] / target[j]);
      if (j < p.log_parameter_se.size() && !std::isnan(p.log_parameter_se[j]))
        worst = std::max(worst, p.log_parameter_se[j] / kLogParameterSe);
    }
  return std::isnan(worst) ? std::numeric_limits<double>::infinity() : worst;
}

SearchOutcome shortest_recipe(const DesignEvaluator& evaluator, const Recipe& recipe,
                              const std::vector<double>& target) {
  return scan(evaluator, target, recipe.limits.longest_s, recipe.x_min, recipe.x_max, !recipe.x_is_rate,
              [&](double x) { return recipe.profile(x); });
}

SearchOutcome shortest_plan(const DesignEvaluator& evaluator, const RigLimits& limits,
                            const std::vector<double>& target, const std::function<void(int, int)>& progress) {
  std::vector<std::pair<int, bool>> families;
  for (int legs = 1; legs <= kMostLegs; ++legs)
    for (bool low_first : {true, false}) families.emplace_back(legs, low_first);
  std::vector<SearchOutcome> outcomes(families.size());
  parallel_for(
      families.size(), threads_at_most(2),
      [&](std::size_t i) {
        outcomes[i] = plan_family(evaluator, limits, target, families[i].first, families[i].second);
      },
      [&](std::size_t done) {
        if (progress) progress(static_cast<int>(done), static_cast<int>(families.size()));
      });
  // In family order, whichever thread finished first: the same answer every run.
  SearchOutcome out;
  out.best.shortfall = std::numeric_limits<double>::infinity();
  for (const SearchOutcome& o : outcomes) {
    out.evaluations += o.evaluations;
    if (better(o.best, out.best)) out.best = o.best;
  }
  out.met = out.best.met();
  return out;
}

}  // namespace gyrotherm::studies::plan
