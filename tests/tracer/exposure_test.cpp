// Auto exposure (tracer/exposure.h): the meter's rule on a sky of known radiance, its response to
// the light, its independence of the render's seed and of the thread count, and a render asked
// for "auto" being the render at the metered exposure.
#include "tracer/exposure.h"

#include <cmath>

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include "spec/scene_desc.h"
#include "scene/render_input.h"
#include "test_world.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"

namespace arbor::tracer {

namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

// The default camera over the default ground under a Preetham sky and a sun, small.
spec::SceneDesc lit_ground() {
  spec::SceneDesc s;
  s.render.width = 48;
  s.render.height = 32;
  s.render.spp = 4;
  s.camera.auto_exposure = true;
  return s;
}

double meter(const spec::SceneDesc& s) {
  const EmbreeDevice device("");
  const TestWorld test_world(s, device);
  const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 64);
  return metered_exposure(scene::render_input(s), test_world.world, sky);
}

}  // namespace

// A constant sky of radiance 0.5 and nothing else: every pixel's luminance is 0.5, and the meter
// puts it at middle grey, log2(0.18 / 0.5) stops.
TEST(AutoExposure, AUniformSkyIsMeteredToMiddleGrey) {
  spec::SceneDesc s = lit_ground();
  s.sun.enabled = false;
  s.ground.enabled = false;
  s.sky.model = spec::SkyModel::Constant;
  s.sky.color = {0.5, 0.5, 0.5};
  EXPECT_NEAR(meter(s), std::log2(0.18 / 0.5), 1e-5);
}

// Twice the light (sun and sky) is one stop less; the render's seed and the thread count change
// nothing, bit for bit.
TEST(AutoExposure, FollowsTheLightAndNothingElse) {
  spec::SceneDesc s = lit_ground();
  s.sky.model = spec::SkyModel::Constant;
  s.sky.color = {0.2, 0.3, 0.4};
  const double base = meter(s);
  std::printf("  metered %+.4f stops\n", base);
  EXPECT_GT(base, -8.0);
  EXPECT_LT(base, 8.0);
  spec::SceneDesc brighter = s;
  brighter.sun.irradiance *= 2.0;
  brighter.sky.color = {0.4, 0.6, 0.8};
  EXPECT_NEAR(meter(brighter), base - 1.0, 1e-3);
  spec::SceneDesc seeded = s;
  seeded.render.seed = 12345;
  EXPECT_EQ(meter(seeded), base);
  double one_thread = 0.0;
  tbb::task_arena(1).execute([&] { one_thread = meter(s); });
  EXPECT_EQ(one_thread, base);
}

// The meter reads the scene, not the output: a transparent sky (the compositing plate), the
// treemaker integrator and regularisation meter the beauty pass's exposure, bit for bit.
TEST(AutoExposure, MetersTheSceneNotTheOutputVariant) {
  const spec::SceneDesc s = lit_ground();
  const double beauty = meter(s);
  spec::SceneDesc plate = s;
  plate.output.transparent_sky = true;
  EXPECT_EQ(meter(plate), beauty);
  spec::SceneDesc approximate = s;
  approximate.render.integrator = spec::Integrator::Treemaker;
  EXPECT_EQ(meter(approximate), beauty);
  spec::SceneDesc regularized = s;
  regularized.render.regularize = true;
  EXPECT_EQ(meter(regularized), beauty);
  // The light still counts: a dimmer sun meters brighter.
  spec::SceneDesc dim = s;
  dim.sun.irradiance *= 0.5;
  EXPECT_GT(meter(dim), beauty + 0.2);
}

// A render asked for "auto" is, pixel for pixel, the render at the metered exposure given as
// stops.
TEST(AutoExposure, TheRenderUsesTheMeteredExposure) {
  const spec::SceneDesc s = lit_ground();
  spec::SceneDesc fixed = s;
  fixed.camera.auto_exposure = false;
  fixed.camera.exposure = meter(s);
  const EmbreeDevice device("");
  const TestWorld test_world(s, device);
  const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 64);
  imaging::RenderStats stats;
  const imaging::Image a =
      render_image(scene::render_input(s), test_world.world, sky, kIdentity, stats);
  const imaging::Image b =
      render_image(scene::render_input(fixed), test_world.world, sky, kIdentity, stats);
  ASSERT_EQ(a.beauty.size(), b.beauty.size());
  for (std::size_t p = 0; p < a.beauty.size(); ++p) ASSERT_EQ(a.beauty[p], b.beauty[p]) << p;
  spec::SceneDesc plain = fixed;
  plain.camera.exposure = 0.0;
  const imaging::Image c =
      render_image(scene::render_input(plain), test_world.world, sky, kIdentity, stats);
  EXPECT_NE(a.beauty[0], c.beauty[0]);  // the metered exposure is not 0 here
}

}  // namespace arbor::tracer
