// The pixel sampler (tracer/sampler.h): points in [0, 1)², stratified, keyed by pixel and seed.
#include "tracer/sampler.h"

#include <cstdint>

#include <gtest/gtest.h>

namespace arbor::tracer {
namespace {

// Every point of the first 16 samples lies in [0, 1)² (checked before it is used as an index:
// a coordinate of 1.0 is the classic float rounding bug) and they fill the 4×4 strata of every
// dimension pair.
TEST(Sampler, FirstSixteenSamplesFillEveryStratum) {
  for (const std::uint32_t pixel : {0u, 1234u, 0xffffffffu}) {
    const PixelSampler s(pixel, 7);
    for (std::uint32_t dim = 0; dim < 16; ++dim) {
      bool seen[4][4] = {};
      for (std::uint32_t i = 0; i < 16; ++i) {
        const glm::vec2 u = s.get2d(i, dim);
        ASSERT_GE(u.x, 0.0f);
        ASSERT_LT(u.x, 1.0f);
        ASSERT_GE(u.y, 0.0f);
        ASSERT_LT(u.y, 1.0f);
        seen[static_cast<int>(u.x * 4)][static_cast<int>(u.y * 4)] = true;
      }
      for (auto& row : seen) {
        for (bool b : row) EXPECT_TRUE(b) << "pixel " << pixel << " dim " << dim;
      }
    }
  }
}

// Different seeds, pixels and passes give different points; the same ones the same points.
TEST(Sampler, KeysDecorrelateAndRepeat) {
  EXPECT_NE(PixelSampler(1, 7).get2d(0, 0), PixelSampler(2, 7).get2d(0, 0));
  EXPECT_NE(PixelSampler(1, 7).get2d(0, 0), PixelSampler(1, 8).get2d(0, 0));
  EXPECT_NE(PixelSampler(1, 7, 0).get2d(0, 0), PixelSampler(1, 7, 1).get2d(0, 0));
  EXPECT_NE(PixelSampler(1, 7).get2d(0, 0), PixelSampler(1, 7 + (1ull << 32)).get2d(0, 0));
  EXPECT_EQ(PixelSampler(5, 9, 3).get2d(11, 4), PixelSampler(5, 9, 3).get2d(11, 4));
}

}  // namespace
}  // namespace arbor::tracer
