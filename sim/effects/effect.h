#pragma once
// A physical effect on the gyro bias, defined once for the simulator and the
// fit (docs/model.md, "Effects"; the term names are a public contract,
// docs/contracts.md).
//
// The bias is linear in the effects' coefficients:
//
//   B(t) = b0 + Σ_k c_k · r_k(t; θ_k)                                  [°/h]
//
// r_k is effect k's regressor, computed from an EffectSeries (the gyro's
// thermal state over time), and θ_k its optional nonlinear parameter (a time
// constant, a dead band). The two sides call the same function:
//
//  * the simulator evaluates r_k on the true physical state at its sample
//    times and adds c_k·r_k to the bias (sim/bias_model.h): that is how an
//    effect is injected, with c_k and θ_k from the gyro file or --hidden;
//  * the fit evaluates r_k on the window means of a measured record
//    (fit/data/derivatives.h) and estimates c_k, and θ_k by variable
//    projection (fit/pipeline.h).
//
// So what is simulated is exactly what is fitted. The paper's terms (T, T^2,
// dT) are effects like any other; their true coefficients come from the gyro
// file's [truth] table, every other effect's from [hidden].
//
// An entry holds everything any layer needs to know about the effect: its
// meaning and unit, the columns it reads, its [truth] key, its parameter, its
// family (from which diagnosis derives what a record can confound), its C
// form (from which `export --format c` writes it) and, for a power of T, the
// power (from which the firmware exports decide whether they can hold it).
// Nothing outside sim/effects/ decides by an effect's name; a test walks the
// registry and fails on an incomplete entry (tests/effects_test.cpp).
//
// Adding an effect: one file sim/effects/NAME.cpp defining
// `extern constinit const Effect NAME{...}` in namespace gyrotherm::effects
// (sim/effects/lag.cpp is a full example, temperature.cpp a pointwise one),
// one test tests/NAME_test.cpp, one line EFFECT(NAME) in
// sim/effects/registry.def. The sources are globbed: CMake needs no edit.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gyrotherm::effects {

// What every regressor reads: one entry per point in time.
struct EffectSeries {
  std::vector<double> time_s;          // since the start of the record
  std::vector<double> temp_c;          // gyro temperature at the sensor location
  std::vector<double> rate_c_per_s;    // dT/dt
  std::vector<double> accel_c_per_s2;  // d²T/dt²
  std::vector<double> temp2_c;         // the far side of the block; empty when not measured
  // When the gyro was switched on, on the time_s clock: 0 at the start of the
  // record, −∞ for a gyro running long before it.
  double switch_on_s = 0.0;
  std::size_t size() const { return temp_c.size(); }
};

// The columns of a measurement an effect needs (docs/contracts.md's names).
enum Column : unsigned { kTime = 1u, kTemp = 2u, kTemp2 = 4u };

// What an effect's regressor follows. Diagnosis derives from it which terms a
// record can confound (studies/diagnose/confounding.h): powers of T and a
// filtered temperature move with the temperature, rates vanish in a soak, a
// time term moves with the clock.
enum class Family {
  temperature_power,  // T^k: a static function of the temperature
  temperature_state,  // the temperature through a filter with memory (lag)
  rate,               // of the temperature's change: 0 in a soak (dT, T*dT, d2T, hyst)
  gradient,           // a temperature difference across the block (grad)
  time,               // the time since the start of the record (t)
  transient,          // a decay from switch-on (warmup)
  // Terms the fit makes, not effects (fit/model/terms.h):
  step,               // step@TIME
  logged,             // a column of the user's log
};

// The regressor in C, at a closed averaging window (`export --format c`,
// studies/export/c_header.cpp). In scope: T and T2 (°C, the window's means of
// temp_c and temp2_c), rate (°C/s) and accel (°C/s²), its backward
// derivatives, and rel (s since the record's first sample). {theta} stands for
// the fitted parameter, printed exactly.
//
// An effect whose regressor has memory (a filter) has a state: `initial` is its
// value at the first window, `expression` its value at every later one, where
// also prev (its own value at the previous window), prev_T (that window's T),
// h (s between the two) and slope = (T − prev_T)/h are in scope.
struct CForm {
  std::string_view expression;
  std::string_view initial = {};
  bool stateful() const { return !initial.empty(); }
};

// A nonlinear parameter of an effect, e.g. a time constant.
struct EffectParameter {
  std::string_view name;      // e.g. "time_constant_s" (the fit's JSON key)
  std::string_view gyro_key;  // its key in a gyro file's [hidden] table
  double lower = 0.0;         // the fit's search bounds (searched on a log scale)
  double upper = 0.0;
  double simulator_default = 0.0;  // the simulator's value when the gyro file is silent
  bool may_be_zero = false;        // the gyro file may set it to 0
  // r is smooth in θ, so the fit can give θ a linearised interval (a dead
  // band, where r jumps, is not).
  bool differentiable = true;
};

struct Effect {
  using Regressor = void (*)(const Effect& self, const EffectSeries& series, double parameter,
                             std::span<double> out);
  std::string_view name;        // the term name: a public contract (docs/contracts.md)
  std::string_view meaning;     // physical meaning, for `gyrotherm effects` and reports
  std::string_view unit;        // of the regressor ("1" when dimensionless)
  unsigned columns = kTemp;     // the Column bits it reads
  // For the paper's terms, the gyro file's [truth] key of the true
  // coefficient (e.g. "b1_dph_per_c"); empty for a hidden effect, whose
  // coefficient is [hidden] NAME = COEF or --hidden NAME=COEF.
  std::string_view truth_key;
  std::optional<EffectParameter> parameter;
  Family family = Family::temperature_power;
  CForm c_form;
  // k for T^k, the power of a polynomial in T a firmware table can hold; 0
  // for any other effect.
  int temperature_power = 0;
  // r(t) at every point of the series; `parameter` is θ (ignored without
  // one). Call it through compute().
  Regressor regressor = nullptr;
  // For an effect with memory (c_form.stateful()): r at point k ≥ 1 from
  // `previous`, r at k − 1, and the series at k − 1 and k; the regressor is
  // this recursion from its first point. The real-time compensator carries r
  // from window to window with it (fit/causal_compensator.h), as the C export
  // carries `prev`. nullptr for an effect without memory.
  using Recursion = double (*)(const EffectSeries& series, std::size_t k, double parameter, double previous);
  Recursion next = nullptr;

  void compute(const EffectSeries& series, double theta, std::span<double> out) const {
    regressor(*this, series, theta, out);
  }

  bool needs_temp2() const { return (columns & kTemp2) != 0; }
  bool hidden() const { return truth_key.empty(); }
  // "°/h per °C", or "°/h" for a dimensionless regressor.
  // "°/h per °C": the bias's unit (a gyro's, or `measured`: "m/s²", "Pa") per the term's.
  std::string coefficient_unit(std::string_view measured = "°/h") const;
  // "temp_c, temp2_c": the columns it reads, by their default names.
  std::string column_names() const;
};

// Every effect, in the order of sim/effects/registry.def.
const std::vector<const Effect*>& registry();
// nullptr if unknown.
const Effect* find(std::string_view name);
// The effect whose [truth] key this is, or nullptr.
const Effect* find_by_truth_key(std::string_view truth_key);
// "T, T^2, T^3, ...": every name, or only the hidden ones.
std::string names();
std::string hidden_names();

// The regressor of an effect whose r at a point depends on that point alone:
// pointwise<f>, f(series, index, θ) → r.
template <auto f>
void pointwise(const Effect&, const EffectSeries& series, double parameter, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = f(series, p, parameter);
}

// T^k at a point: T·T·…·T, multiplied left to right.
template <int k>
double temperature_power(const EffectSeries& series, std::size_t p, double) {
  double r = series.temp_c[p];
  for (int i = 1; i < k; ++i) r *= series.temp_c[p];
  return r;
}

// A power of T as an effect: the entry's family, power and regressor from k;
// the file gives its name, meaning, unit, [truth] key and C form.
template <int k>
constexpr Effect power_of_temperature(Effect entry) {
  entry.family = Family::temperature_power;
  entry.temperature_power = k;
  entry.regressor = pointwise<&temperature_power<k>>;
  return entry;
}

// r at every point of a series, as a new vector.
std::vector<double> regressor_values(const Effect& effect, const EffectSeries& series,
                                     double parameter);

}  // namespace gyrotherm::effects
