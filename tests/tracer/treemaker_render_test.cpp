// The treemaker integrator: Figure 3's factors against hand-worked values, MAX_INTENSITY and the
// rendered shade against the formula, the tree extent h0/r0, the weights' sources, the ground
// shadow's place, and determinism.
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "tracer/film.h"
#include "tracer/render.h"
#include "tracer/integrators/treemaker.h"
#include "tracer/lights/sky.h"
#include "tracer/embree/world.h"
#include "tracer/test_world.h"
#include "common/math.h"

namespace arbor::tracer {

namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

std::string write_file(const char* name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// A skeleton with a known extent: a 4 m trunk from (1, 2, 0) and one branch reaching 3 m out
// horizontally (to x = 4) at height 3 m, and a twig up to 5 m.
std::string known_skeleton() {
  return write_file("tm_known.skel",
                    "point 1 1 2 0 0.2\npoint 2 1 2 2 0.15\npoint 3 1 2 4 0.1\n"
                    "point 4 2.5 2 2.5 0.05\npoint 5 4 2 3 0.03\npoint 6 1 2.5 5 0.02\n"
                    "connect 1 2\nconnect 2 3\nconnect 2 4\nconnect 4 5\nconnect 3 6\n");
}

spec::TreeDesc tree_of(const std::string& species) {
  spec::TreeDesc t;
  t.species = species;
  return t;
}

}  // namespace

TEST(Treemaker, FactorsMatchHandWorkedValues) {
  scene::TreeExtent tree;
  tree.base = {1.0f, 1.0f, 0.5f};
  tree.height = 10.0f;
  tree.radius = 5.0f;
  // Sun from +x, 30° up.
  const glm::vec3 L(std::cos(kPi / 6), 0.0f, std::sin(kPi / 6));
  const glm::vec3 up(0.0f, 0.0f, 1.0f);

  // A leaf 3 m towards the sun from the axis, 4 m up.
  TreemakerTerms t = treemaker_terms(tree, {4.0f, 1.0f, 4.5f}, up, false, L);
  EXPECT_FLOAT_EQ(t[0], 1.0f);
  EXPECT_NEAR(t[1], 0.5f, 1e-6f);  // N·L = sin 30°
  EXPECT_NEAR(t[2], 0.4f, 1e-6f);  // 4 / 10
  EXPECT_NEAR(t[3], 0.6f, 1e-6f);  // 3 / 5
  EXPECT_NEAR(t[4], 1.0f, 1e-6f);  // on the sun's side: q = π
  // The same leaf turned over: TREE-MAKER shades the side facing the light.
  EXPECT_NEAR(treemaker_terms(tree, {4.0f, 1.0f, 4.5f}, -up, false, L)[1], 0.5f, 1e-6f);
  // On the far side: q = 0; at right angles: q = π/2.
  EXPECT_NEAR(treemaker_terms(tree, {-2.0f, 1.0f, 4.5f}, up, false, L)[4], 0.0f, 1e-6f);
  EXPECT_NEAR(treemaker_terms(tree, {1.0f, 3.0f, 4.5f}, up, false, L)[4], std::sqrt(0.5f), 1e-6f);
  // 60° round from the sun: q = 120°, sin 60°.
  const glm::vec3 at60(1.0f + std::cos(kPi / 3), 1.0f + std::sin(kPi / 3), 2.0f);
  EXPECT_NEAR(treemaker_terms(tree, at60, up, false, L)[4], std::sin(kPi / 3), 1e-6f);
  // A vertical limb: its normal in the plane of T and L makes N·L = cos 30°.
  EXPECT_NEAR(treemaker_terms(tree, {4.0f, 1.0f, 4.5f}, up, true, L)[1], std::cos(kPi / 6), 1e-6f);
  // A limb pointing at the sun has no lit side in that plane.
  EXPECT_NEAR(treemaker_terms(tree, {4.0f, 1.0f, 4.5f}, L, true, L)[1], 0.0f, 1e-3f);
  // On the axis, or with the light at the zenith, q is taken as π/2.
  EXPECT_NEAR(treemaker_terms(tree, {1.0f, 1.0f, 3.0f}, up, false, L)[4], std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(treemaker_terms(tree, {4.0f, 1.0f, 3.0f}, up, false, up)[4], std::sqrt(0.5f), 1e-6f);

  const materials::TreemakerWeights w{0.1, 0.4, 0.4, 0.3, 0.2};  // the dogwood's light {}
  EXPECT_NEAR(treemaker_shade(w, t), 0.1 + 0.4 * 0.5 + 0.4 * 0.4 + 0.3 * 0.6 + 0.2 * 1.0, 1e-6);
}

TEST(Treemaker, SkyIrradianceOfAConstantSkyIsPiL) {
  spec::SkyDesc sky;
  sky.model = spec::SkyModel::Constant;
  sky.color = {0.5, 1.0, 2.0};
  spec::SunDesc sun;
  sun.enabled = false;
  const Sky s(sky, sun, xyz_to_scene_linear(), 256);
  EXPECT_NEAR(s.irradiance_up().x, kPi * 0.5, 2e-3 * kPi);
  EXPECT_NEAR(s.irradiance_up().y, kPi * 1.0, 2e-3 * kPi);
  EXPECT_NEAR(s.irradiance_up().z, kPi * 2.0, 2e-3 * kPi);
}

TEST(Treemaker, TreeExtentIsMeasuredFromTheFirstPoint) {
  spec::SceneDesc scene;
  spec::TreeDesc t = tree_of(known_skeleton());
  t.placement.position = {10.0, 0.0, 0.0};
  t.placement.scale = 2.0;
  t.placement.rotation = 90.0;
  scene.trees.push_back(t);
  scene.ground.enabled = false;
  const EmbreeDevice device("");
  const TestWorld test_world(scene, device);
  const World& world = test_world.world;
  const scene::TreeExtent& e = world.extent(0);
  // Base (1, 2, 0) rotated 90° about z → (−2, 1, 0), × 2, + (10, 0, 0).
  EXPECT_NEAR(e.base.x, 6.0f, 1e-5f);
  EXPECT_NEAR(e.base.y, 2.0f, 1e-5f);
  EXPECT_NEAR(e.base.z, 0.0f, 1e-5f);
  EXPECT_NEAR(e.height, 2.0f * 5.0f, 1e-5f);  // the twig's tip at 5 m
  EXPECT_NEAR(e.radius, 2.0f * 3.0f, 1e-5f);  // point 5, 3 m out
}

TEST(Treemaker, WeightsComeFromTheTemplateThenTheScene) {
  spec::SceneDesc scene;
  scene.trees.push_back(tree_of(std::string(ARBOR_SOURCE_DIR) + "/species/dogwood.tmpl"));
  spec::TreeDesc overridden = scene.trees.back();
  overridden.treemaker.angle = 0.7;
  scene.trees.push_back(overridden);
  scene.trees.push_back(tree_of(known_skeleton()));
  const EmbreeDevice device("");
  const TestWorld test_world(scene, device);
  const World& world = test_world.world;
  const materials::TreemakerWeights& dogwood =
      world.instance(0).treemaker;  // light { 0.1 0.4 0.4 0.3 0.2 }
  EXPECT_DOUBLE_EQ(dogwood.ambient, 0.1);
  EXPECT_DOUBLE_EQ(dogwood.lambert, 0.4);
  EXPECT_DOUBLE_EQ(dogwood.height, 0.4);
  EXPECT_DOUBLE_EQ(dogwood.radius, 0.3);
  EXPECT_DOUBLE_EQ(dogwood.angle, 0.2);
  EXPECT_DOUBLE_EQ(world.instance(1).treemaker.angle, 0.7);
  EXPECT_DOUBLE_EQ(world.instance(1).treemaker.height, 0.4);
  // A tree of another model gets arbor's documented defaults (docs/treemaker-format.md).
  const materials::TreemakerWeights& other = world.instance(2).treemaker;
  EXPECT_DOUBLE_EQ(other.ambient, 0.1);
  EXPECT_DOUBLE_EQ(other.lambert, 0.4);
  EXPECT_DOUBLE_EQ(other.height, 0.2);
  EXPECT_DOUBLE_EQ(other.radius, 0.2);
  EXPECT_DOUBLE_EQ(other.angle, 0.1);
}

// The shade worked out from the view alone, without the integrator's AOVs: a vertical trunk
// (T = z) under a sun 30° up has N·L = sqrt(1 − (T·L)²) = cos 30° everywhere, and h/h0 is the
// hit's height over the trunk's 10 m, which a horizontal camera sees row by row.
TEST(Treemaker, ShadeOfAVerticalTrunkIsWorkedOutFromTheView) {
  spec::SceneDesc s;
  s.render.width = 16;
  s.render.height = 64;
  s.render.treemaker_spp = 1;
  s.render.integrator = spec::Integrator::Treemaker;
  s.camera.position = {0.0, -20.0, 5.0};
  s.camera.look_at = {0.0, 0.0, 5.0};
  s.camera.fov = 40.0;
  s.sun.elevation = 30.0;
  s.sun.azimuth = 0.0;
  s.sun.irradiance = 2.0;
  s.sky.model = spec::SkyModel::None;
  s.ground.enabled = false;
  spec::TreeDesc t =
      tree_of(write_file("tm_pole.skel", "point 1 0 0 0 0.3\npoint 2 0 0 10 0.3\nconnect 1 2\n"));
  t.bark.albedo = Rgb{0.5, 0.5, 0.5};
  t.treemaker = {0.0, 1.0, 0.0, 0.0, 0.0};  // N·L alone
  s.trees.push_back(t);
  const double max_intensity = 2.0 / kPi;  // (E_sun + E_sky) / π with no sky
  const double tan_half = std::tan(20.0 * kPi / 180.0);
  const EmbreeDevice device("");
  for (int part = 0; part < 2; ++part) {
    if (part == 1) s.trees[0].treemaker = {0.0, 0.0, 1.0, 0.0, 0.0};  // h/h0 alone
    const TestWorld test_world(s, device);
    const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 64);
    imaging::RenderStats stats;
    const imaging::Image img =
        render_image(scene::render_input(s), test_world.world, sky, kIdentity, stats);
    int trunk = 0;
    for (int y = 0; y < s.render.height; ++y) {
      // The height the row's centre sees on the trunk's front (19.7 m away), and what one pixel
      // of the tent filter's reach spans there.
      const double slope = tan_half * (1.0 - 2.0 * (y + 0.5) / s.render.height);
      const double z = 5.0 + 19.7 * slope, z_pixel = 19.7 * 2.0 * tan_half / s.render.height;
      for (int x = 6; x < 10; ++x) {  // the trunk's middle columns
        const std::size_t p = static_cast<std::size_t>(y) * s.render.width + x;
        if (img.depth[p] <= 0.0f || z < 0.3 || z > 9.7) continue;
        ++trunk;
        if (part == 0) {
          EXPECT_NEAR(img.beauty[p].x, 0.5 * max_intensity * std::cos(kPi / 6.0), 1e-5)
              << "row " << y;
        } else {
          EXPECT_NEAR(img.beauty[p].x, 0.5 * max_intensity * z / 10.0,
                      0.5 * max_intensity * 1.5 * z_pixel / 10.0)
              << "row " << y;
        }
      }
    }
    EXPECT_GT(trunk, 60) << "part " << part;  // the 0.6 m trunk is three pixels wide
  }
}

// The AOVs' identity: every pixel of a tree is albedo × MAX_INTENSITY × Σ w·factor of its own
// factors, with MAX_INTENSITY = (E_sun + E_sky)/π (the factors themselves are checked from the
// view in ShadeOfAVerticalTrunkIsWorkedOutFromTheView). Ground pixels, worked out independently,
// are ρ(E_sun cos θ + E_sky)/π in sunlight and ρ E_sky/π in the tree's shadow, which lies on the
// side away from the sun.
TEST(Treemaker, RenderedShadeAndGroundShadowFollowTheFormula) {
  spec::SceneDesc s;
  s.render.width = 64;
  s.render.height = 64;
  s.render.treemaker_spp = 1;
  s.render.integrator = spec::Integrator::Treemaker;
  s.output.aovs = {};
  s.output.aovs.add(imaging::Aov::Treemaker);
  s.camera.position = {0.0, 0.0, 60.0};  // straight down onto the tree and its shadow
  s.camera.look_at = {0.0, 0.0, 0.0};
  s.camera.up = {0.0, 1.0, 0.0};
  s.camera.fov = 20.0;
  s.sun.elevation = 45.0;
  s.sun.azimuth = 0.0;  // from +x: shadows fall towards −x
  s.sun.irradiance = 2.0;
  s.sky.model = spec::SkyModel::Constant;
  s.sky.color = {0.25, 0.25, 0.25};
  s.ground.albedo = {0.5, 0.5, 0.5};
  spec::TreeDesc t = tree_of(known_skeleton());
  t.placement.position = {-1.0, -2.0, 0.0};  // base at the origin
  t.placement.scale = 1.5;
  t.treemaker.ambient = 0.3;
  s.trees.push_back(t);
  const EmbreeDevice device("");
  const TestWorld test_world(s, device);
  const World& world = test_world.world;
  const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 256);
  const TreemakerIntegrator integrator(world, sky);
  const float e_sky = sky.irradiance_up().x;
  EXPECT_NEAR(integrator.max_intensity().x, (2.0f + e_sky) / kPi, 1e-5);

  imaging::RenderStats stats;
  const imaging::Image img = render_image(scene::render_input(s), world, sky, kIdentity, stats);
  const float lit = static_cast<float>(0.5 * (2.0 * std::sin(kPi / 4) + e_sky) / kPi);
  const float shadow = static_cast<float>(0.5 * e_sky / kPi);
  const std::size_t channels = img.extra_names.size();
  int tree = 0, lit_pixels = 0, shadow_pixels = 0;
  double shadow_x = 0.0;
  const materials::TreemakerWeights& w = world.instance(0).treemaker;
  for (int y = 0; y < s.render.height; ++y) {
    for (int x = 0; x < s.render.width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * s.render.width + x;
      const float* extra = &img.extra[p * channels];
      const float v = img.beauty[p].x;
      if (extra[0] > 0.0f) {
        ++tree;
        // One sample per pixel: the pixel is one element's shade.
        TreemakerTerms terms;
        for (int i = 0; i < 5; ++i) terms[static_cast<size_t>(i)] = extra[i];
        EXPECT_NEAR(v, img.albedo[p].x * integrator.max_intensity().x * treemaker_shade(w, terms),
                    1e-5f);
        continue;
      }
      if (std::fabs(v - lit) < 1e-5f) {
        ++lit_pixels;
      } else {
        EXPECT_NEAR(v, shadow, 1e-5f) << "ground pixel " << x << ", " << y;
        ++shadow_pixels;
        shadow_x += x;
      }
    }
  }
  EXPECT_GT(tree, 10);
  EXPECT_GT(lit_pixels, 1000);
  ASSERT_GT(shadow_pixels, 10);
  // The camera looks down with +y up in the image, so +x in the world is +x in the image; the
  // trunk's foot is at the image centre and the shadow lies towards −x.
  EXPECT_LT(shadow_x / shadow_pixels, s.render.width / 2.0 - 3.0);
}

TEST(Treemaker, ImagesAreBitIdenticalAtOneAndTwoThreadsWithOrWithoutAovs) {
  spec::SceneDesc s;
  s.render.width = 48;
  s.render.height = 32;
  s.render.treemaker_spp = 3;
  s.render.integrator = spec::Integrator::Treemaker;
  s.output.aovs = {};
  s.output.aovs.add(imaging::Aov::Treemaker);
  s.camera.position = {9.0, -12.0, 4.0};
  s.camera.look_at = {0.0, 0.0, 6.0};
  spec::TreeDesc t = tree_of(std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml");
  s.trees.push_back(t);
  imaging::Image images[2];
  for (int threads : {1, 2}) {
    s.render.threads = threads;
    const EmbreeDevice device("threads=" + std::to_string(threads));
    const TestWorld test_world(s, device);
    const World& world = test_world.world;
    const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 128);
    imaging::RenderStats stats;
    images[threads - 1] = render_image(scene::render_input(s), world, sky, kIdentity, stats);
  }
  ASSERT_EQ(images[0].extra.size(), images[1].extra.size());
  ASSERT_EQ(images[0].extra.size(), 48u * 32u * 23u);
  EXPECT_EQ(std::memcmp(images[0].beauty.data(), images[1].beauty.data(),
                        images[0].beauty.size() * sizeof(glm::vec3)),
            0);
  EXPECT_EQ(std::memcmp(images[0].extra.data(), images[1].extra.data(),
                        images[0].extra.size() * sizeof(float)),
            0);
  // Without the AOV nothing extra is kept, and the beauty is the same.
  s.output.aovs = {};
  const EmbreeDevice device("threads=2");
  const TestWorld test_world(s, device);
  const World& world = test_world.world;
  const Sky sky(s.sky, s.sun, xyz_to_scene_linear(), 128);
  imaging::RenderStats stats;
  const imaging::Image plain = render_image(scene::render_input(s), world, sky, kIdentity, stats);
  EXPECT_TRUE(plain.extra.empty());
  EXPECT_TRUE(plain.extra_names.empty());
  EXPECT_EQ(std::memcmp(plain.beauty.data(), images[1].beauty.data(),
                        plain.beauty.size() * sizeof(glm::vec3)),
            0);
}

}  // namespace arbor::tracer
