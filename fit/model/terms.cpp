#include "fit/model/terms.h"

#include <cmath>
#include <limits>

namespace gyrotherm::fit {
namespace {

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

Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters) {
  const auto l = static_cast<Eigen::Index>(derived.size());
  Eigen::MatrixXd x(l, static_cast<Eigen::Index>(terms.size()));
  for (std::size_t j = 0; j < terms.size(); ++j)
    terms[j]->regressor(derived, parameters[j],
                        std::span<double>(x.col(static_cast<Eigen::Index>(j)).data(),
                                          static_cast<std::size_t>(l)));
  return x;
}

std::vector<double> default_parameters(const std::vector<const Term*>& terms) {
  std::vector<double> p(terms.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t j = 0; j < terms.size(); ++j)
    if (terms[j]->parameter) p[j] = std::sqrt(terms[j]->parameter->lower * terms[j]->parameter->upper);
  return p;
}

}  // namespace gyrotherm::fit
