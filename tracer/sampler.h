// Low-discrepancy samples keyed by (pixel, pass, sample index, dimension, seed): padded 2D Sobol'
// points with hash-based Owen scrambling (Burley 2020). No state, so any thread and tile order
// gives the same numbers.
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec2.hpp>

namespace arbor::tracer {

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Laine–Karras style permutation of a bit-reversed value (the hash only carries upward, so in
// reversed bit order it scrambles each bit by the bits above it: an Owen scramble of r).
constexpr std::uint32_t laine_karras(std::uint32_t r, std::uint32_t seed) {
  r += seed;
  r ^= r * 0x6c50b47cu;
  r ^= r * 0xb82f1e52u;
  r ^= r * 0xc7afe638u;
  r ^= r * 0x8d22f6e6u;
  return r;
}
// Owen scramble of x: the permutation above applied to x's bits reversed, reversed back.
constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(x), seed));
}

constexpr std::uint32_t hash32(std::uint32_t a, std::uint32_t b) {
  std::uint64_t x = (static_cast<std::uint64_t>(a) << 32) ^ b ^ 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return static_cast<std::uint32_t>(x ^ (x >> 31));
}

// The samples of one pixel; dimension pairs are independent scrambles of the 2D Sobol' points.
class PixelSampler {
 public:
  // Pass 0 keeps the key a single-pass render always had; every other pass scrambles anew, so
  // pass means are independent replicates (randomised QMC).
  PixelSampler(std::uint32_t pixel, std::uint64_t seed, std::uint32_t pass = 0)
      : key_(hash32(pixel, static_cast<std::uint32_t>(seed) ^
                               hash32(static_cast<std::uint32_t>(seed >> 32), 0x51ed27u))) {
    if (pass != 0) key_ = hash32(key_ ^ 0x7a55e5u, pass);
  }

  // The 2D point of sample `index` in dimension pair `dim`, in [0, 1)².
  glm::vec2 get2d(std::uint32_t index, std::uint32_t dim) const {
    const std::uint32_t s = hash32(key_, dim);
    const std::uint32_t i = owen_scramble(index, s);  // shuffles the order per dimension pair
    // owen_scramble of the first Sobol' dimension (i reversed) and of the second, with the
    // reversal inside owen_scramble cancelled against the points' own (bit for bit the same).
    const std::uint32_t x = reverse_bits(laine_karras(i, hash32(s, 1)));
    const std::uint32_t y = reverse_bits(laine_karras(sobol_second_reversed(i), hash32(s, 2)));
    return {to_unit(x), to_unit(y)};
  }
  float get1d(std::uint32_t index, std::uint32_t dim) const { return get2d(index, dim).x; }

  // For tests: the second dimension's byte tables give what its bit loop gives, reversed.
  static bool sobol_tables_agree(std::uint32_t i) {
    return sobol_second_reversed(i) == reverse_bits(sobol_second_bits(i));
  }

 private:
  // Second dimension of the Sobol' sequence (generator matrix with v_k = 1 + 2 v_{k-1} pattern):
  // the XOR of the direction numbers of i's set bits; sobol_second_reversed looks its bit reversal
  // up a byte at a time.
  static constexpr std::uint32_t sobol_second_bits(std::uint32_t i) {
    std::uint32_t r = 0;
    for (std::uint32_t v = 1u << 31; i; i >>= 1, v ^= v >> 1) {
      if (i & 1u) r ^= v;
    }
    return r;
  }
  using ByteTables = std::array<std::array<std::uint32_t, 256>, 4>;
  static constexpr ByteTables sobol_second_tables() {
    ByteTables t{};
    for (std::uint32_t k = 0; k < 4; ++k) {
      // Bit reversal commutes with XOR, so the tables hold the reversed direction numbers.
      for (std::uint32_t b = 0; b < 256; ++b)
        t[k][b] = reverse_bits(sobol_second_bits(b << (8 * k)));
    }
    return t;
  }
  static std::uint32_t sobol_second_reversed(std::uint32_t i) {
    static constexpr ByteTables t = sobol_second_tables();
    return t[0][i & 0xffu] ^ t[1][(i >> 8) & 0xffu] ^ t[2][(i >> 16) & 0xffu] ^ t[3][i >> 24];
  }

  static constexpr float to_unit(std::uint32_t x) {
    return static_cast<float>(x >> 8) * 0x1.0p-24f;  // 24 bits: strictly below 1 in float
  }
  std::uint32_t key_;
};

}  // namespace arbor::tracer
