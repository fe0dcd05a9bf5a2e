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

// A generator for one component, derived from the run's seed and a fixed stream id.
Rng make_rng(std::uint64_t seed, std::uint64_t stream);

namespace streams {
inline constexpr std::uint64_t arw = 1;
inline constexpr std::uint64_t flicker = 2;
inline constexpr std::uint64_t rrw = 3;
inline constexpr std::uint64_t quantizer = 4;
inline constexpr std::uint64_t glitch = 5;
// Temperature reading i uses stream reading_base + i.
inline constexpr std::uint64_t reading_base = 16;
}  // namespace streams

}  // namespace gyrotherm
