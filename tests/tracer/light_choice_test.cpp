// Which light next-event estimation samples: a smooth sky is left to BSDF sampling, a peaked one
// is light-sampled; the sky's cosine-sampling variance against its closed form.
#include <cmath>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include "common/math.h"
#include "tracer/test_world.h"
#include "tracer/integrators/path.h"
#include "tracer/lights/sky.h"

namespace arbor::tracer {

namespace {

spec::SunDesc no_sun() {
  spec::SunDesc sun;
  sun.enabled = false;
  return sun;
}

// A lat-long map of radiance 1 in the rows above polar angle π rows / height, 0 elsewhere.
std::string write_cap(int rows, int height) {
  const std::string path = ::testing::TempDir() + "cap_" + std::to_string(rows) + ".exr";
  OIIO::ImageBuf env(OIIO::ImageSpec(2 * height, height, 3, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < 2 * height; ++x) {
      const float v = y < rows ? 1.0f : 0.0f;
      const float px[3] = {v, v, v};
      env.setpixel(x, y, px);
    }
  }
  EXPECT_TRUE(env.write(path));
  return path;
}

Sky cap_sky(int rows, int height) {
  spec::SkyDesc desc;
  desc.model = spec::SkyModel::Envmap;
  desc.path = write_cap(rows, height);
  return Sky(desc, no_sun(), xyz_to_scene_linear(), 2 * height);
}

}  // namespace

TEST(LightChoice, CosineVarianceOfAConstantSkyIsZero) {
  spec::SkyDesc desc;
  desc.model = spec::SkyModel::Constant;
  desc.color = {0.12, 0.18, 0.3};
  const Sky sky(desc, no_sun(), xyz_to_scene_linear(), 256);
  EXPECT_NEAR(sky.cosine_variance_up(), 0.0f, 1e-3f);
}

TEST(LightChoice, CosineVarianceOfACapIsCotSquaredOfItsAngle) {
  // Radiance 1 within θ0 of the zenith: E = π sin²θ0, ∫ L² cos θ dω = π sin²θ0, so the relative
  // variance π ∫ L² cos θ dω / E² − 1 is 1 / sin²θ0 − 1 = cot²θ0.
  for (const int rows : {4, 8, 16, 32}) {
    const Sky sky = cap_sky(rows, 64);
    const double theta0 = kPi * rows / 64.0;
    const double expected = 1.0 / std::tan(theta0) / std::tan(theta0);
    EXPECT_NEAR(sky.cosine_variance_up(), expected, 0.02 * expected + 1e-3) << rows << " rows";
  }
}

// The cases the rule was measured on (docs/rendering.md, "Light selection"): each decision is
// the one that rendered with the higher efficiency.
TEST(LightChoice, TheSkyIsLightSampledWhereThatMeasuredBetter) {
  const auto choice = [](spec::SkyModel model, double elevation, bool sun_on) {
    spec::SkyDesc desc;
    desc.model = model;
    desc.color = {0.12, 0.18, 0.3};
    desc.dust_density = 3.0;
    spec::SunDesc sun;
    sun.enabled = sun_on;
    sun.elevation = elevation;
    sun.irradiance = 3.0;
    const Sky sky(desc, sun, xyz_to_scene_linear(), 256);
    return PathIntegrator::light_choice(sky);
  };
  using M = spec::SkyModel;
  // Constant sky and sun (the Cycles yardstick): every shadow ray to the sun.
  PathIntegrator::LightChoice c = choice(M::Constant, 38.0, true);
  EXPECT_EQ(c.sun, 1.0f);
  EXPECT_EQ(c.sky, 0.0f);
  // Preetham at 38° (V 0.28, S/K 2.0) and Nishita at 40° with dust 3 (V 2.09, S/K 5.7): the sun.
  EXPECT_EQ(choice(M::Preetham, 38.0, true).sky, 0.0f);
  EXPECT_EQ(choice(M::Nishita, 40.0, true).sky, 0.0f);
  // Nishita at 10° (V 5.5, S/K 1.4): the sky too, sharing by irradiance.
  c = choice(M::Nishita, 10.0, true);
  EXPECT_GT(c.sky, 0.1f);
  EXPECT_NEAR(c.sun + c.sky, 1.0f, 1e-6f);
  // Preetham without its sun (V 0.28): no shadow rays at all.
  c = choice(M::Preetham, 38.0, false);
  EXPECT_EQ(c.sun + c.sky, 0.0f);
  // Caps without a sun: V = 1 (θ0 = 45°) and V = 25 (θ0 = π/16) are light-sampled.
  for (const int rows : {16, 4}) {
    c = PathIntegrator::light_choice(cap_sky(rows, 64));
    EXPECT_EQ(c.sun, 0.0f) << rows;
    EXPECT_EQ(c.sky, 1.0f) << rows;
  }
  // Nothing to sample: no sky, no sun.
  c = choice(M::None, 38.0, false);
  EXPECT_EQ(c.sun + c.sky, 0.0f);
}

}  // namespace arbor::tracer
