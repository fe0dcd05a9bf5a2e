// lag: the cavity's temperature as a first-order thermal lag behind the
// sensor's, r = T_lag (°C) with
//
//     τ·dT_lag/dt = T − T_lag,    T_lag(t₀) = T(t₀)  (in equilibrium at the start),
//
// τ (s) the parameter. Between two points T is taken as linear in time, for
// which the update is exact whatever the spacing (first-order hold):
//
//     s = (T_k − T_{k−1})/h,  e = exp(−h/τ),
//     T_lag,k = T_k − τ·s + e·(T_lag,k−1 − T_{k−1} + τ·s),
//
// so the simulator's 1 Hz samples and the fit's window means (gaps
// included, bridged linearly) describe the same filter. On a steady ramp
// T_lag = T − τ·dT/dt; what sets it apart from T and dT is how it settles
// after the rate changes.
#include <cmath>

#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

double next(const EffectSeries& s, std::size_t k, double tau_s, double previous) {
  const double h = s.time_s[k] - s.time_s[k - 1];
  const double slope = (s.temp_c[k] - s.temp_c[k - 1]) / h;
  const double e = std::exp(-h / tau_s);
  return s.temp_c[k] - tau_s * slope + e * (previous - s.temp_c[k - 1] + tau_s * slope);
}

void regressor(const Effect&, const EffectSeries& s, double tau_s, std::span<double> out) {
  if (out.empty()) return;
  out[0] = s.temp_c[0];
  for (std::size_t k = 1; k < out.size(); ++k) out[k] = next(s, k, tau_s, out[k - 1]);
}

}  // namespace

extern constinit const Effect lag{
    .name = "lag",
    .meaning = "sensor-to-cavity thermal lag (first order)",
    .unit = "°C",
    .columns = kTime | kTemp,
    .parameter = EffectParameter{.name = "time_constant_s",
                                 .gyro_key = "lag_time_constant_s",
                                 .lower = 60.0,
                                 .upper = 4.0 * 3600.0,
                                 .simulator_default = 1200.0},
    .family = Family::temperature_state,
    // The same update in C, on the windows of the real-time compensator.
    .c_form = {.expression = "T - {theta} * slope + exp(-h / {theta}) * (prev - prev_T + {theta} * slope)",
               .initial = "T"},
    .regressor = &regressor,
    .next = &next,
};

}  // namespace gyrotherm::effects
