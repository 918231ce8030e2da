// Tests of image textures: the luminance of a height map, the texel a sample at a pixel centre
// returns, and the refusal of non-finite heights and of albedos outside [0, 1].
#include <cmath>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "materials/textures.h"

namespace arbor::materials {
namespace {

// A 2x2 linear EXR whose pixel (1, 0) is `odd` and the others `base`.
std::string write_image(const char* name, const float base[3], const float odd[3]) {
  const std::string path = ::testing::TempDir() + name;
  OIIO::ImageBuf buf(OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 2; ++x) buf.setpixel(x, y, x == 1 && y == 0 ? odd : base);
  }
  EXPECT_TRUE(buf.write(path));
  return path;
}

const std::string kConfig = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

TEST(Textures, HeightMapTakesTheRec709Luminance) {
  const float base[3] = {0.0f, 0.0f, 0.0f}, odd[3] = {1.0f, 0.5f, 0.25f};
  const HeightMap map(write_image("height.exr", base, odd));
  ASSERT_EQ(map.width(), 2);
  // Pixel (1, 0)'s centre is at u = 0.75, v = 0.25.
  EXPECT_NEAR(map.sample(0.75, 0.25), 0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25, 1e-6);
  EXPECT_NEAR(map.sample(0.25, 0.75), 0.0, 1e-6);
}

TEST(Textures, ColorMapReturnsItsTexels) {
  const float base[3] = {0.1f, 0.2f, 0.3f}, odd[3] = {0.9f, 0.5f, 0.0f};
  const ColorMap map(write_image("albedo.exr", base, odd), kConfig);
  const glm::vec3 c = map.sample(0.75, 0.25);
  EXPECT_NEAR(c.x, 0.9f, 1e-6);
  EXPECT_NEAR(c.y, 0.5f, 1e-6);
  EXPECT_NEAR(c.z, 0.0f, 1e-6);
}

TEST(Textures, BadTexelsAreRefusedWithTheirPosition) {
  const float base[3] = {0.1f, 0.2f, 0.3f}, bright[3] = {1.5f, 0.5f, 0.0f},
              nan[3] = {std::nanf(""), 0.0f, 0.0f};
  const std::string over = write_image("albedo_over.exr", base, bright);
  arbor::testing::expect_input_error([&] { ColorMap(over, kConfig); }, over, 0, 0,
                                     "albedo texels must be in [0, 1]; pixel (1, 0) is not");
  const std::string holed = write_image("height_nan.exr", base, nan);
  arbor::testing::expect_input_error([&] { HeightMap{holed}; }, holed, 0, 0, "not finite");
  const std::string missing = ::testing::TempDir() + "no_such_texture.png";
  arbor::testing::expect_input_error([&] { HeightMap{missing}; }, missing, 0, 0,
                                     "image does not exist");
}

}  // namespace
}  // namespace arbor::materials
