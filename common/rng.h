// Deterministic random streams keyed by identity, so one part of a model never reshuffles another.
#pragma once

#include <cstdint>

namespace arbor {

// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Derives a child key from a parent key and a label (order matters: (a,b) != (b,a)).
constexpr std::uint64_t derive_key(std::uint64_t parent, std::uint64_t label) {
  return mix64(parent ^ mix64(label + 0x632be59bd9b4e019ull));
}

// A small, fast generator (SplitMix64 sequence) started from a key. Identical on every platform.
class Rng {
 public:
  explicit constexpr Rng(std::uint64_t key) : state_(mix64(key)) {}

  constexpr std::uint64_t next_u64() {
    state_ += 0x9e3779b97f4a7c15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  // Uniform in [-1, 1).
  double symmetric() { return 2.0 * uniform() - 1.0; }
  // The papers' "value ± variation": uniform in [value - variation, value + variation).
  double vary(double value, double variation) { return value + variation * symmetric(); }

 private:
  std::uint64_t state_;
};

}  // namespace arbor
