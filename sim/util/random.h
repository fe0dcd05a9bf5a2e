#pragma once
// Deterministic random generators, one per noise component.
//
// Every component (ARW, flicker, RRW, quantiser phase, glitches, each
// temperature reading) owns a Mersenne Twister seeded from the run's seed and a
// fixed stream id:
//
//     key = splitmix64(splitmix64(seed) ⊕ stream),
//     generator = mt19937_64(key).
//
// SplitMix64 (Steele, Lea & Flood 2014) is a bijective 64-bit finaliser with
// full avalanche: for a fixed seed the map stream → key is one-to-one, and so
// is seed → key for a fixed stream, while neighbouring seeds or streams give
// unrelated keys ((seed, stream) = (1, 2) and (2, 1) are unrelated too).
// Because a component draws only from its own stream, switching one component
// on or off never changes the numbers another one sees.
//
// Draw with boost::random distributions (normal_distribution,
// uniform_real_distribution, exponential_distribution, bernoulli_distribution):
// unlike std:: distributions, their algorithms are fixed, so the same seed gives
// the same numbers on every platform and standard library.
//
// References: G. L. Steele, D. Lea, C. H. Flood, "Fast splittable pseudorandom
// number generators", OOPSLA 2014; M. Matsumoto, T. Nishimura, "Mersenne
// Twister", ACM TOMACS 8 (1998).

#include <cstdint>

#include <boost/random/mersenne_twister.hpp>

namespace gyrotherm {

using Rng = boost::random::mt19937_64;

// The SplitMix64 output function applied to x (a bijection of 64-bit words).
std::uint64_t splitmix64(std::uint64_t x);
// The SplitMix64 sequence: the next value from `state` (which it advances);
// the first value from state x equals splitmix64(x).
std::uint64_t splitmix64_next(std::uint64_t& state);

// A generator for one component, derived from the run's seed and a fixed stream id.
Rng make_rng(std::uint64_t seed, std::uint64_t stream);

// Every stream id of the project, in one place, so that no two components
// share one by accident. A component draws only from make_rng(seed, its id).
namespace streams {
enum : std::uint64_t {
  // The simulator's noise (sim/noise.h), one per component; temperature
  // reading i uses stream reading_base + i.
  arw = 1, flicker = 2, rrw = 3, quantizer = 4, glitch = 5, reading_base = 16,
  // The white noise of a gyro file's channel i (sim/channel.h): channel_base + i.
  channel_base = 64,
  // The fish-swarm engines' own generators (fit/engines/afsa.h, iafsa.h).
  afsa = 0xAF5A, iafsa = 0x1AF5A,
  // The bootstrap of diagnose's likelihood test (studies/diagnose/likelihood_test.h).
  diagnosis_likelihood_bootstrap = 0x11B0,
  // The per-trial [spread] draws of score (studies/score/spread.h).
  score_spread = 0x5C0E,
  // ols's parametric bootstrap of the coefficients (fit/model/noise_bootstrap.h).
  fit_bootstrap = 0xB007,
};
}  // namespace streams

}  // namespace gyrotherm
