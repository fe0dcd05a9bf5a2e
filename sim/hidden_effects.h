#pragma once
// The physical effects the simulator can hide in the bias, by the term names of
// DESIGN.md (a public contract shared with fit/'s effect registry). Each is
// computed from the true physical temperatures, never from the noisy readings:
//
//   grad     T_far − T_anode                       °C      coefficient in °/h per °C
//   T*dT     T · dT/dt                             °C²/s   °/h per °C²/s
//   T^3      T³                                    °C³     °/h per °C³
//   d2T      d²T/dt²                               °C/s²   °/h per °C/s²
//   hyst     +1 heating, −1 cooling, 0 inside the dead band |dT/dt| ≤ d
//                                                  1       °/h
//   warmup   exp(−t/τ), t since switch-on          1       °/h (the offset at switch-on)
//   t        time since switch-on                  h       °/h per hour
//
// T is the anode-side block temperature (where the Pt800 sits), in °C.

#include <array>
#include <string>
#include <string_view>

namespace gyrotherm::sim {

struct HiddenTerm {
  std::string_view name;
  std::string_view meaning;
  std::string_view coefficient_unit;
};

inline constexpr std::array<HiddenTerm, 7> kHiddenTerms{{
    {"grad", "temperature gradient across the block (Langmuir-flow imbalance)", "°/h per °C"},
    {"T*dT", "rate sensitivity that changes with temperature", "°/h per °C²/s"},
    {"T^3", "higher-order curvature of the temperature sensitivity", "°/h per °C³"},
    {"d2T", "sensor-to-cavity thermal lag", "°/h per °C/s²"},
    {"hyst", "heating/cooling hysteresis", "°/h"},
    {"warmup", "turn-on transient", "°/h"},
    {"t", "slow drift, ageing", "°/h per h"},
}};

bool is_hidden_term(std::string_view name);
// "grad, T*dT, T^3, d2T, hyst, warmup, t"
std::string hidden_term_list();

}  // namespace gyrotherm::sim
