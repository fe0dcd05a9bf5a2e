#include "fit/terms.h"

#include <cmath>

namespace gyrotherm::fit {
namespace {

// Central differences within each run (one-sided at its ends), or backward
// differences (0 at the first window of a run) for the causal mode.
std::vector<double> differentiate(const std::vector<double>& t_s, const std::vector<double>& x,
                                  const std::vector<std::size_t>& run, DerivativeMode mode) {
  const std::size_t n = x.size();
  std::vector<double> d(n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const bool has_prev = p > 0 && run[p - 1] == run[p];
    const bool has_next = p + 1 < n && run[p + 1] == run[p];
    std::size_t lo = p, hi = p;
    if (mode == DerivativeMode::causal) {
      if (has_prev) lo = p - 1;
    } else {
      if (has_prev) lo = p - 1;
      if (has_next) hi = p + 1;
    }
    if (hi != lo) d[p] = (x[hi] - x[lo]) / (t_s[hi] - t_s[lo]);
  }
  return d;
}

void reg_t(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.temp_c[p];
}
void reg_t2(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.temp_c[p] * d.temp_c[p];
}
void reg_t3(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.temp_c[p] * d.temp_c[p] * d.temp_c[p];
}
void reg_dt(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.rate_c_per_s[p];
}
void reg_tdt(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.temp_c[p] * d.rate_c_per_s[p];
}
void reg_d2t(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.accel_c_per_s2[p];
}
void reg_grad(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.grad_c[p];
}
void reg_hyst(const DerivedSeries& d, double dead_band, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) {
    const double r = d.rate_c_per_s[p];
    out[p] = r > dead_band ? 1.0 : (r < -dead_band ? -1.0 : 0.0);
  }
}
void reg_warmup(const DerivedSeries& d, double tau_s, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = std::exp(-d.time_h[p] * 3600.0 / tau_s);
}
void reg_time(const DerivedSeries& d, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = d.time_h[p];
}

}  // namespace

DerivedSeries derive(const AveragedSeries& data, DerivativeMode mode) {
  DerivedSeries d;
  d.temp_c = data.temp_c;
  d.time_h.reserve(data.size());
  for (double t : data.time_s) d.time_h.push_back((t - data.start_time_s) / 3600.0);
  d.rate_c_per_s = differentiate(data.time_s, data.temp_c, data.run, mode);
  d.accel_c_per_s2 = differentiate(data.time_s, d.rate_c_per_s, data.run, mode);
  if (!data.temp2_c.empty()) {
    d.grad_c.resize(data.size());
    for (std::size_t p = 0; p < data.size(); ++p) d.grad_c[p] = data.temp2_c[p] - data.temp_c[p];
  }
  return d;
}

const std::vector<Term>& term_registry() {
  static const std::vector<Term> terms = {
      {"T", "temperature sensitivity", "°C", false, std::nullopt, &reg_t},
      {"T^2", "curvature of the sensitivity", "°C²", false, std::nullopt, &reg_t2},
      {"T^3", "higher-order curvature", "°C³", false, std::nullopt, &reg_t3},
      {"dT", "temperature-rate effect (cavity bending, gas flow)", "°C/s", false, std::nullopt,
       &reg_dt},
      {"T*dT", "rate sensitivity that changes with temperature", "°C²/s", false, std::nullopt,
       &reg_tdt},
      {"d2T", "sensor-to-cavity thermal lag", "°C/s²", false, std::nullopt, &reg_d2t},
      {"grad", "temperature gradient across the block (Langmuir-flow imbalance)", "°C", true,
       std::nullopt, &reg_grad},
      {"hyst", "heating/cooling hysteresis", "1", false,
       TermParameter{"dead_band_c_per_s", 1e-6, 2e-3, true}, &reg_hyst},
      {"warmup", "turn-on transient", "1", false,
       TermParameter{"time_constant_s", 60.0, 7200.0, true}, &reg_warmup},
      {"t", "slow drift, ageing", "h", false, std::nullopt, &reg_time},
  };
  return terms;
}

const Term* find_term(std::string_view name) {
  for (const Term& t : term_registry())
    if (t.name == name) return &t;
  return nullptr;
}

std::string term_list() {
  std::string out;
  for (const Term& t : term_registry()) out += (out.empty() ? "" : ", ") + t.name;
  return out;
}

}  // namespace gyrotherm::fit
