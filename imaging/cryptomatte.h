// Cryptomatte (Friedman & Jones, "Cryptomatte specification" 1.2.0): ids from names by
// MurmurHash3_x86_32, as floats, and the manifest and header keys of a layer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace arbor::imaging {

// MurmurHash3_x86_32 of the bytes of `text` (Appleby's reference algorithm).
std::uint32_t murmur3_32(const std::string& text, std::uint32_t seed = 0);

// The specification's id of a name: its hash with bit 23 flipped when the exponent would make a
// float denormal, infinite or NaN, read as a float.
std::uint32_t cryptomatte_hash(const std::string& name);
float cryptomatte_id(const std::string& name);

// Eight lower-case hex digits.
std::string hex8(std::uint32_t value);

// The layer's metadata key: the first 7 hex digits of the hash of its name
// ("cryptomatte/<key>/name" and so on).
std::string cryptomatte_key(const std::string& layer);

// {"name": "hex8 of its hash", …} in the order given.
std::string cryptomatte_manifest(const std::vector<std::string>& names);

}  // namespace arbor::imaging
