#include "sim/util/random.h"

namespace gyrotherm {

std::uint64_t splitmix64_next(std::uint64_t& state) {
  // Steele, Lea & Flood (2014): add the golden-ratio increment, then the
  // variant-13 finaliser of MurmurHash3 (Stafford's constants).
  std::uint64_t x = (state += 0x9E3779B97F4A7C15ULL);
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

std::uint64_t splitmix64(std::uint64_t x) { return splitmix64_next(x); }

Rng make_rng(std::uint64_t seed, std::uint64_t stream) {
  // Hash the seed before mixing in the stream so that no simple relation
  // between the two (seed ⊕ stream = const, say) makes two keys coincide; the
  // outer hash spreads a one-bit stream difference over the whole key.
  const std::uint64_t key = splitmix64(splitmix64(seed) ^ stream);
  return Rng(key);
}

}  // namespace gyrotherm
