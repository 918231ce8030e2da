// Cryptomatte's ids: MurmurHash3_x86_32 against published vectors, the float conversion that
// avoids denormals, infinities and NaN, the layer key and the manifest.
#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "imaging/cryptomatte.h"

namespace arbor::imaging {

TEST(Cryptomatte, MurmurHashMatchesTheReferenceVectors) {
  // Vectors of Appleby's reference implementation (SMHasher), seed 0 unless given.
  EXPECT_EQ(murmur3_32(""), 0u);
  EXPECT_EQ(murmur3_32("", 1), 0x514e28b7u);
  EXPECT_EQ(murmur3_32("hello"), 0x248bfa47u);
  EXPECT_EQ(murmur3_32("Hello, world!", 1234), 0xfaf6cdb3u);
  EXPECT_EQ(murmur3_32("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
  // Every tail length (0 to 3 bytes past a block).
  EXPECT_EQ(murmur3_32("a"), 0x3c2569b2u);
  EXPECT_EQ(murmur3_32("ab"), 0x9bbfd75fu);
  EXPECT_EQ(murmur3_32("abc"), 0xb3dd93fau);
  EXPECT_EQ(murmur3_32("abcd"), 0x43ed676au);
}

TEST(Cryptomatte, IdsAreFiniteNormalFloatsOfTheHash) {
  int flipped = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::string name = "tree." + std::to_string(i);
    const float id = cryptomatte_id(name);
    EXPECT_TRUE(std::isnormal(id)) << name;
    std::uint32_t bits;
    std::memcpy(&bits, &id, sizeof bits);
    const std::uint32_t h = murmur3_32(name);
    const std::uint32_t exponent = (h >> 23) & 0xffu;
    // Only a hash whose exponent is all zeros or all ones changes, by bit 23 alone.
    if (exponent == 0 || exponent == 0xff) {
      EXPECT_EQ(bits, h ^ (1u << 23)) << name;
      ++flipped;
    } else {
      EXPECT_EQ(bits, h) << name;
    }
    EXPECT_EQ(bits, cryptomatte_hash(name));
  }
  EXPECT_GT(flipped, 50);  // about 2/256 of the names
}

TEST(Cryptomatte, KeyAndManifest) {
  EXPECT_EQ(hex8(0x0000abcdu), "0000abcd");
  EXPECT_EQ(cryptomatte_key("crypto_object"), hex8(murmur3_32("crypto_object")).substr(0, 7));
  EXPECT_EQ(cryptomatte_manifest({"ground", "quaking_aspen.0"}),
            "{\"ground\": \"" + hex8(cryptomatte_hash("ground")) + "\", \"quaking_aspen.0\": \"" +
                hex8(cryptomatte_hash("quaking_aspen.0")) + "\"}");
}

}  // namespace arbor::imaging
