// Cryptomatte ids and manifests.
#include "imaging/cryptomatte.h"

#include <cstdio>
#include <cstring>

#include "common/json.h"

namespace arbor::imaging {

namespace {
std::uint32_t rotl(std::uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }
}  // namespace

std::uint32_t murmur3_32(const std::string& text, std::uint32_t seed) {
  const auto* data = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t len = text.size();
  const std::uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
  std::uint32_t h = seed;
  const std::size_t blocks = len / 4;
  for (std::size_t i = 0; i < blocks; ++i) {
    // Blocks read little-endian, whatever the machine.
    std::uint32_t k = std::uint32_t(data[4 * i]) | std::uint32_t(data[4 * i + 1]) << 8 |
                      std::uint32_t(data[4 * i + 2]) << 16 | std::uint32_t(data[4 * i + 3]) << 24;
    k *= c1;
    k = rotl(k, 15);
    k *= c2;
    h ^= k;
    h = rotl(h, 13);
    h = h * 5u + 0xe6546b64u;
  }
  const unsigned char* tail = data + 4 * blocks;
  std::uint32_t k = 0;
  switch (len & 3u) {
    case 3: k ^= std::uint32_t(tail[2]) << 16; [[fallthrough]];
    case 2: k ^= std::uint32_t(tail[1]) << 8; [[fallthrough]];
    case 1:
      k ^= tail[0];
      k *= c1;
      k = rotl(k, 15);
      k *= c2;
      h ^= k;
  }
  h ^= static_cast<std::uint32_t>(len);
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

std::uint32_t cryptomatte_hash(const std::string& name) {
  std::uint32_t h = murmur3_32(name);
  const std::uint32_t exponent = (h >> 23) & 0xffu;
  if (exponent == 0 || exponent == 0xffu) h ^= 1u << 23;
  return h;
}

float cryptomatte_id(const std::string& name) {
  const std::uint32_t h = cryptomatte_hash(name);
  float f;
  std::memcpy(&f, &h, sizeof f);
  return f;
}

std::string hex8(std::uint32_t value) {
  char buf[12];
  std::snprintf(buf, sizeof buf, "%08x", value);
  return buf;
}

std::string cryptomatte_key(const std::string& layer) {
  return hex8(murmur3_32(layer)).substr(0, 7);
}

std::string cryptomatte_manifest(const std::vector<std::string>& names) {
  JsonObject manifest;
  for (const std::string& n : names) manifest.text(n, hex8(cryptomatte_hash(n)));
  return manifest.str();
}

}  // namespace arbor::imaging
