#include "studies/diagnose/confounding.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sim/util/format.h"
#include "sim/util/input_error.h"

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

Separation separate(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                    const fit::Term* a, const fit::Term* b) {
  std::vector<const fit::Term*> with = model;
  with.push_back(a);
  with.push_back(b);
  const fit::ModelFit f = fit::fit_model(data, with, fit::find_engine("ols"), {});
  const auto& iv = f.engine.intervals;
  if (iv.size() < 2) throw InputError("the joint model gave no intervals");
  const fit::Interval ia = iv[iv.size() - 2], ib = iv.back();
  Separation s;
  s.a_adds = ia.lower > 0.0 || ia.upper < 0.0;
  s.b_adds = ib.lower > 0.0 || ib.upper < 0.0;
  if (!s.a_adds && !s.b_adds)
    s.note = fmt::format(
        "{} and {} explain the same part of the bias on this record: fitted together, neither adds "
        "significantly to what the other explains (95 % intervals under the record's identified noise: {} "
        "[{:.3g}, {:.3g}], {} [{:.3g}, {:.3g}]); a record on which they differ (other temperature rates or "
        "gradients) would separate them",
        a->name, b->name, a->name, ia.lower, ia.upper, b->name, ib.lower, ib.upper);
  return s;
}

void add_group(Confounding& c, const std::string& a, const std::string& b, const std::string& note) {
  // Every group holding a or b becomes one, with their notes joined.
  std::vector<std::string> merged = {a, b};
  std::string notes;
  for (std::size_t g = 0; g < c.groups.size();) {
    const auto& group = c.groups[g];
    const bool holds = std::find(group.begin(), group.end(), a) != group.end() ||
                       std::find(group.begin(), group.end(), b) != group.end();
    if (!holds) {
      ++g;
      continue;
    }
    std::vector<std::string> front = group;
    for (const std::string& t : merged)
      if (std::find(front.begin(), front.end(), t) == front.end()) front.push_back(t);
    merged = std::move(front);
    if (g < c.notes.size()) {
      notes += (notes.empty() ? "" : "; ") + c.notes[g];
      c.notes.erase(c.notes.begin() + static_cast<std::ptrdiff_t>(g));
    }
    c.groups.erase(c.groups.begin() + static_cast<std::ptrdiff_t>(g));
  }
  c.groups.push_back(std::move(merged));
  c.notes.push_back(notes.empty() ? note : notes + "; " + note);
}

const std::vector<std::string>* Confounding::group_of(const std::string& term) const {
  for (const auto& g : groups)
    if (std::find(g.begin(), g.end(), term) != g.end()) return &g;
  return nullptr;
}

Confounding find_confounding(const fit::DerivedSeries& derived, const std::vector<const fit::Term*>& terms,
                             const std::vector<double>& parameters) {
  Confounding out;
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
  const char* direction = cooling_share > 0.9   ? "it only cools"
                          : cooling_share < 0.1 ? "it only heats"
                                                : "temperature follows time";

  for (const auto& group : members) {
    if (group.size() < 2) continue;
    std::vector<std::string> names;
    bool has_time = false, has_temp = false, has_rate = false, has_offset = false;
    for (std::size_t i : group) {
      names.push_back(i == n ? std::string("1") : std::string(terms[i]->name));
      if (i == n) {
        has_offset = true;
        continue;
      }
      has_time |= terms[i]->family == effects::Family::time;
      has_temp |= is_temperature(*terms[i]);
      has_rate |= is_rate(*terms[i]);
    }
    std::string list;
    for (std::size_t k = 0; k < names.size(); ++k)
      list += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") +
              (names[k] == "1" ? std::string("a constant offset") : names[k]);
    std::string why, test;
    if (has_time && has_temp) {
      why = fmt::format("temperature and time move together on this record (r = {:.3f}: {})", r_time,
                        direction);
      test = "a test with both a heating and a cooling leg, or a soak, would separate them";
    } else if (has_offset && has_rate) {
      double rate_mean = 0.0;
      for (double r : derived.rate_c_per_s) rate_mean += r;
      rate_mean /= static_cast<double>(derived.size());
      why = fmt::format("the temperature changes at an almost constant rate ({} °C/h), so a rate "
                        "effect acts as a constant offset",
                        human(rate_mean * 3600.0));
      test = "a test with varied rates (ramps and soaks) would separate them";
    } else if (has_temp && has_rate) {
      why = "the temperature settles along one curve, its rate moving with its distance from the "
            "end value, so temperature and rate effects look alike";
      test = "a test with ramps at several rates and soaks would separate them";
    } else if (has_temp) {
      const auto [lo, hi] = std::minmax_element(derived.temp_c.begin(), derived.temp_c.end());
      why = fmt::format("over the record's {}..{} °C their regressors are nearly proportional",
                        human(*lo), human(*hi));
      test = "a wider temperature range would separate them";
    } else {
      why = "their regressors are nearly proportional over this record";
      test = "a test with another profile would separate them";
    }
    out.notes.push_back(fmt::format("{} cannot be told apart on this record: {}; {}.", list, why, test));
    out.groups.push_back(std::move(names));
  }
  return out;
}

}  // namespace gyrotherm::studies
