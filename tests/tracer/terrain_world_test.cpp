// Tests of the terrain in the Embree world: the surface Embree renders is the one Terrain::height
// states (so what is placed by it stands on what is seen), on the steepest terrain arbor makes;
// every tree of a forest on it has its base on that surface; terrain hits carry the ground's
// material, a shading normal that is the smooth one and the rock cover of steep faces.
#include <cmath>
#include <cstdio>
#include <vector>

#include <OpenImageIO/imageio.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/rng.h"
#include "formats/scene_desc.h"
#include "test_world.h"

namespace arbor::tracer {
namespace {

// Mountains of 400 m relief over 600 m, at 2 m: slopes past 60° on the ridges.
const char* const kMountains =
    "[terrain]\nkind = \"mountains\"\nsize = 600\nrelief = 400\nresolution = 2\nseed = 3\n";

// The height Embree renders at (x, y): a ray from far below, straight up, and its first hit
// (the terrain is seen from both sides); NaN when it hits nothing or not the terrain.
double rendered_height(const World& world, double x, double y) {
  Ray up;
  up.origin = glm::vec3(static_cast<float>(x), static_cast<float>(y), -100.0f);
  up.direction = glm::vec3(0.0f, 0.0f, 1.0f);
  WorldHit hit;
  if (!world.intersect(up, hit) || !hit.ground) return std::nan("");
  return static_cast<double>(up.origin.z) + hit.surface.t;
}

TEST(TerrainWorld, TheRenderedSurfaceIsTheOneHeightStates) {
  const formats::SceneDesc desc =
      formats::parse_scene(std::string(kMountains) + "[ground]\nenabled = false\n", "terrain.toml");
  const EmbreeDevice device;
  const TestWorld w(desc, device);
  const scene::Terrain& t = w.scene->terrain;
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(t.columns(), 301);
  EXPECT_NEAR(t.relief(), 400.0, 1e-9);
  Rng rng(5);
  double worst = 0.0, steepest = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double x = -290.0 + 580.0 * rng.uniform(), y = -290.0 + 580.0 * rng.uniform();
    const double h = rendered_height(w.world, x, y);
    ASSERT_TRUE(std::isfinite(h)) << x << ", " << y;
    worst = std::max(worst, std::abs(h - t.height(x, y)));
    steepest = std::max(steepest, t.slope(x, y));
  }
  EXPECT_LT(worst, 2e-3);  // metres: float precision at 400 m
  EXPECT_GT(steepest, 60.0);
}

TEST(TerrainWorld, EveryTreeOfAForestStandsOnTheSurface) {
  const formats::SceneDesc desc = formats::parse_scene(
      std::string(kMountains) + "[ground]\nenabled = false\n[[forest]]\nspecies = \"" +
          ARBOR_SOURCE_DIR +
          "/species/lsystem_weed.lsys\"\ncount = 200\nvariants = 2\n"
          "area = [[-250.0, -250.0], [250.0, 250.0]]\n",
      "forest.toml");
  const EmbreeDevice device;
  const TestWorld w(desc, device);
  ASSERT_EQ(w.scene->instances.size(), 200u);
  for (const scene::TreeInstance& inst : w.scene->instances) {
    const glm::vec3 base = inst.extent.base;
    EXPECT_NEAR(base.z, rendered_height(w.world, base.x, base.y), 0.01) << base.x << ", " << base.y;
  }
}

struct Faces {
  int steep = 0, gentle = 0, bare = 0;  // steep: > 50°, all rock; gentle: < 10°, bare: no rock
};

Faces look_down(const std::string& terrain) {
  const formats::SceneDesc desc = formats::parse_scene(terrain, "terrain.toml");
  const EmbreeDevice device;
  const TestWorld w(desc, device);
  const scene::Terrain& t = w.scene->terrain;
  Rng rng(9);
  Faces f;
  for (int k = 0; k < 4000; ++k) {
    Ray down;
    down.origin = glm::vec3(-280.0f + 560.0f * static_cast<float>(rng.uniform()),
                            -280.0f + 560.0f * static_cast<float>(rng.uniform()), 1000.0f);
    down.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    WorldHit hit;
    EXPECT_TRUE(w.world.intersect(down, hit));
    EXPECT_TRUE(hit.ground);
    EXPECT_EQ(hit.material, &w.scene->ground);
    EXPECT_EQ(w.scene->object_names.at(hit.object_id - 1), "terrain");
    const glm::vec3 p = hit.surface.position;
    EXPECT_GT(glm::dot(hit.surface.shading_normal, t.normal(p.x, p.y)), 0.9999f);
    EXPECT_GT(hit.surface.geometric_normal.z, 0.0f);  // facing the ray, which came from above
    const double slope = t.slope(p.x, p.y);
    if (slope > 50.0) {
      ++f.steep;
      EXPECT_EQ(hit.surface.terrain.y, 1.0f) << slope;
    } else if (slope < 10.0) {
      ++f.gentle;
      f.bare += hit.surface.terrain.y == 0.0f;
    }
  }
  return f;
}

TEST(TerrainWorld, HitsAreTheGroundWithTheSmoothNormalAndRockOnSteepFaces) {
  EXPECT_GT(look_down(kMountains).steep, 100);
  // Gentle ground is mostly not rock (valley floors, hollows; summits and ridges are).
  const Faces hills =
      look_down("[terrain]\nkind = \"hills\"\nsize = 600\nrelief = 60\nresolution = 2\nseed = 3\n");
  EXPECT_GT(hills.gentle, 400);
  EXPECT_GT(hills.bare, 0.6 * hills.gentle) << hills.gentle;
}

// A plane rising at `degrees` towards +x as an EXR elevation image, 64 × 64 pixels 0.5 m apart.
std::string slope_image(const std::string& name, double degrees) {
  const std::string path = ::testing::TempDir() + name;
  std::vector<float> px(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      px[static_cast<std::size_t>(y * 64 + x)] =
          static_cast<float>(0.5 * x * std::tan(degrees * 3.14159265358979 / 180.0));
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(64, 64, 1, OIIO::TypeDesc::FLOAT);
  EXPECT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
  out->close();
  return path;
}

// A tree on a 30° slope: its trunk vertical, its base on the surface, and the ground met all
// round — a ray running 5 cm above the slope towards the trunk's axis meets the trunk's near
// side (without the trunk continued below its base, downhill it passes under the flare and meets
// the far wall from inside).
TEST(TerrainWorld, ATreeOnASlopeMeetsItAllRound) {
  const std::string dem = slope_image("slope30.exr", 30.0);
  for (const char* species : {"quaking_aspen.toml", "lsystem_weed.lsys"}) {
    const formats::SceneDesc desc = formats::parse_scene(
        "[terrain]\nkind = \"image\"\npath = \"" + dem +
            "\"\nmetres_per_pixel = 0.5\n[ground]\nenabled = false\n[[tree]]\nspecies = \"" +
            ARBOR_SOURCE_DIR + "/species/" + species + "\"\n",
        "slope.toml");
    const EmbreeDevice device;
    const TestWorld w(desc, device);
    const scene::Terrain& t = w.scene->terrain;
    const glm::vec3 base = w.scene->instances.at(0).extent.base;
    EXPECT_NEAR(base.z, t.height(base.x, base.y), 0.01);
    const glm::vec3 axis(base.x, base.y, 0.0f);
    for (int k = 0; k < 16; ++k) {
      const double a = 2.0 * 3.14159265358979 * k / 16.0;
      const glm::vec3 out = axis + 1.5f * glm::vec3(std::cos(a), std::sin(a), 0.0f);
      const glm::vec3 from(out.x, out.y, static_cast<float>(t.height(out.x, out.y) + 0.05));
      const glm::vec3 to(axis.x, axis.y, static_cast<float>(t.height(axis.x, axis.y) + 0.05));
      Ray r;
      r.origin = from;
      r.direction = glm::normalize(to - from);
      WorldHit hit;
      ASSERT_TRUE(w.world.intersect(r, hit)) << species << " azimuth " << k;
      EXPECT_EQ(hit.instance, 0) << species << " azimuth " << k;
      EXPECT_LT(hit.surface.t, glm::length(to - from)) << species << " azimuth " << k;
    }
  }
}

}  // namespace
}  // namespace arbor::tracer
