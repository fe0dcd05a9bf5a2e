#include "studies/diagnose/confounding.h"

#include <algorithm>
#include <cmath>
#include <numeric>


namespace gyrotherm::studies {
namespace {

double mean_of(const Eigen::VectorXd& v) { return v.mean(); }

double sd_of(const Eigen::VectorXd& v) {
  if (v.size() < 2) return 0.0;
  return std::sqrt((v.array() - v.mean()).square().sum() / static_cast<double>(v.size() - 1));
}

double correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::ArrayXd da = a.array() - a.mean(), db = b.array() - b.mean();
  const double den = std::sqrt(da.square().sum() * db.square().sum());
  return den > 0.0 ? (da * db).sum() / den : 0.0;
}

// What a term moves with, from its family (sim/effects/effect.h).
bool is_temperature(const fit::Term& t) {
  return t.family == effects::Family::temperature_power || t.family == effects::Family::temperature_state;
}
bool is_rate(const fit::Term& t) { return t.family == effects::Family::rate; }

// Smallest root with path halving.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

void add_group(std::vector<ConfoundingGroup>& groups, const ConfoundingEvidence& e) {
  // Every group holding a or b becomes one, with their evidence joined.
  ConfoundingGroup merged;
  merged.members = {e.a, e.b};
  for (std::size_t g = 0; g < groups.size();) {
    if (!groups[g].holds(e.a) && !groups[g].holds(e.b)) {
      ++g;
      continue;
    }
    std::vector<std::string> front = groups[g].members;
    for (const std::string& t : merged.members)
      if (std::find(front.begin(), front.end(), t) == front.end()) front.push_back(t);
    merged.members = std::move(front);
    merged.evidence.insert(merged.evidence.end(), groups[g].evidence.begin(), groups[g].evidence.end());
    groups.erase(groups.begin() + static_cast<std::ptrdiff_t>(g));
  }
  merged.evidence.push_back(e);
  groups.push_back(std::move(merged));
}

bool ConfoundingGroup::holds(const std::string& term) const {
  return std::find(members.begin(), members.end(), term) != members.end();
}

std::vector<ConfoundingGroup> find_confounding(const fit::DerivedSeries& derived,
                                               const std::vector<const fit::Term*>& terms,
                                               const std::vector<double>& parameters) {
  std::vector<ConfoundingGroup> out;
  const std::size_t n = terms.size();
  if (derived.size() < 3 || n == 0) return out;
  const Eigen::MatrixXd x = fit::design_matrix(derived, terms, parameters);
  // Node n stands for the intercept.
  std::vector<std::size_t> parent(n + 1);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> constant(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::VectorXd xi = x.col(static_cast<Eigen::Index>(i));
    // Only a rate has a natural zero against which "nearly constant" means
    // something (a steady cooling rate); a logged voltage of 28 ± 0.4 V varies.
    const double m = mean_of(xi);
    constant[i] = is_rate(*terms[i]) && m != 0.0 &&
                  sd_of(xi) < kNearlyConstant * std::abs(m);
    if (constant[i]) parent[root(parent, i)] = root(parent, n);
    for (std::size_t j = 0; j < i; ++j)
      if (std::abs(correlation(xi, x.col(static_cast<Eigen::Index>(j)))) > kConfoundedCorrelation)
        parent[root(parent, i)] = root(parent, j);
  }
  std::vector<std::vector<std::size_t>> members(n + 1);
  for (std::size_t i = 0; i <= n; ++i) members[root(parent, i)].push_back(i);

  // How the record moves, for the sentences.
  const Eigen::VectorXd temp = Eigen::Map<const Eigen::VectorXd>(
      derived.temp_c.data(), static_cast<Eigen::Index>(derived.size()));
  const Eigen::VectorXd time = Eigen::Map<const Eigen::VectorXd>(
      derived.time_s.data(), static_cast<Eigen::Index>(derived.size()));
  const double r_time = correlation(temp, time);
  const std::size_t cooling = static_cast<std::size_t>(
      std::count_if(derived.rate_c_per_s.begin(), derived.rate_c_per_s.end(), [](double r) { return r < 0.0; }));
  const double cooling_share = static_cast<double>(cooling) / static_cast<double>(derived.size());
  const Direction direction = cooling_share > 0.9   ? Direction::cools
                              : cooling_share < 0.1 ? Direction::heats
                                                    : Direction::both;

  for (const auto& group : members) {
    if (group.size() < 2) continue;
    ConfoundingGroup g;
    bool has_time = false, has_temp = false, has_rate = false, has_offset = false, has_state = false;
    for (std::size_t i : group) {
      g.members.push_back(i == n ? std::string("1") : std::string(terms[i]->name));
      if (i == n) {
        has_offset = true;
        continue;
      }
      has_time |= terms[i]->family == effects::Family::time;
      has_temp |= is_temperature(*terms[i]);
      has_state |= terms[i]->family == effects::Family::temperature_state;
      has_rate |= is_rate(*terms[i]);
    }
    ConfoundingEvidence e;
    if (has_time && has_temp) {
      e.reason = ConfoundingReason::temperature_follows_time;
      e.correlation = r_time;
      e.direction = direction;
    } else if (has_offset && has_rate) {
      double rate_mean = 0.0;
      for (double r : derived.rate_c_per_s) rate_mean += r;
      e.reason = ConfoundingReason::constant_rate;
      e.rate_c_per_h = rate_mean / static_cast<double>(derived.size()) * 3600.0;
    } else if (has_temp && has_rate) {
      e.reason = ConfoundingReason::settling_curve;
    } else if (has_state) {
      // A lagged temperature differs from T by about τ·dT/dt: the record's
      // rates, not its range, decide whether they can be told apart.
      e.reason = ConfoundingReason::lag_follows_temperature;
      for (double r : derived.rate_c_per_s) e.fastest_rate_c_per_min = std::max(e.fastest_rate_c_per_min, std::abs(r) * 60.0);
    } else if (has_temp) {
      const auto [lo, hi] = std::minmax_element(derived.temp_c.begin(), derived.temp_c.end());
      e.reason = ConfoundingReason::narrow_range;
      e.temp_min_c = *lo;
      e.temp_max_c = *hi;
    } else {
      e.reason = ConfoundingReason::proportional;
    }
    g.evidence.push_back(e);
    out.push_back(std::move(g));
  }
  return out;
}

}  // namespace gyrotherm::studies
