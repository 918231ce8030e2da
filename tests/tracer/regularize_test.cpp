// Tests of path regularisation (`[render] regularize`): the camera's first hit is untouched (a
// render of direct light alone is bit-identical), later glossy bounces are roughened (the images
// differ), and the bias it adds to the image mean stays within its documented bound.
#include <cmath>

#include <gtest/gtest.h>

#include "scene/render_input.h"
#include "test_world.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"

namespace arbor::tracer {
namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

// A glossy-leaved aspen (cuticle roughness 0.35: GGX α 0.12, regularised to 0.245) under a low
// sun and a constant sky, its crown filling the frame.
spec::SceneDesc glossy_aspen(bool regularize, int max_depth) {
  spec::SceneDesc s;
  s.render.width = 48;
  s.render.height = 36;
  s.render.spp = 64;
  s.render.max_depth = max_depth;
  s.render.regularize = regularize;
  s.camera.position = {9.0, -12.0, 5.0};
  s.camera.look_at = {0.0, 0.0, 7.0};
  s.camera.focus_distance = 15.0;
  s.sun.elevation = 25.0;
  s.sun.azimuth = 60.0;
  s.sky.model = spec::SkyModel::Constant;
  s.sky.color = {0.3, 0.4, 0.6};
  spec::TreeDesc t;
  t.species = std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml";
  t.seed = 3;
  t.leaf.cuticle_ior = 1.45;
  t.leaf.cuticle_roughness = 0.35;
  s.trees.push_back(t);
  return s;
}

imaging::Image render(const spec::SceneDesc& scene) {
  const EmbreeDevice device;
  const TestWorld w(scene, device);
  const Sky sky(scene.sky, scene.sun, xyz_to_scene_linear(), 64);
  imaging::RenderStats stats;
  return render_image(scene::render_input(scene), w.world, sky, kIdentity, stats);
}

double mean(const imaging::Image& img) {
  double sum = 0.0;
  for (const auto& p : img.beauty) sum += p[0] + p[1] + p[2];
  return sum / (3.0 * static_cast<double>(img.beauty.size()));
}

TEST(Regularize, TheCamerasFirstHitIsUntouched) {
  // max_depth 1: light reaches the camera off the first hit only (its next-event estimate and
  // the sky its sampled direction finds), so regularising later bounces changes nothing.
  const imaging::Image off = render(glossy_aspen(false, 1)), on = render(glossy_aspen(true, 1));
  ASSERT_EQ(off.beauty.size(), on.beauty.size());
  for (std::size_t p = 0; p < off.beauty.size(); ++p) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(off.beauty[p][c], on.beauty[p][c]) << p;
  }
}

TEST(Regularize, RoughensLaterBouncesWithinItsBiasBound) {
  const imaging::Image off = render(glossy_aspen(false, 8)), on = render(glossy_aspen(true, 8));
  int differ = 0;
  for (std::size_t p = 0; p < off.beauty.size(); ++p) differ += off.beauty[p] != on.beauty[p];
  EXPECT_GT(differ, static_cast<int>(off.beauty.size()) / 4);
  // The bound docs/rendering.md states for the image mean: 0.5 % (measured here 0.9996; the
  // coat reflects a few per cent, so even α = 1 everywhere moves it only to 0.9985 — the rule
  // itself is tested in tests/materials/cuticle_test.cpp).
  EXPECT_NEAR(mean(on) / mean(off), 1.0, 0.005) << mean(on) << " " << mean(off);
}

}  // namespace
}  // namespace arbor::tracer
