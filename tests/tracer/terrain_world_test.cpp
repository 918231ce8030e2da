// Tests of the terrain in the Embree world: the surface Embree renders is the one Terrain::height
// states (so what is placed by it stands on what is seen), on the steepest terrain arbor makes;
// every tree of a forest on it has its base on that surface; terrain hits carry the ground's
// material, a shading normal that is the smooth one and the rock cover of steep faces.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <OpenImageIO/imageio.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/rng.h"
#include "formats/scene_file.h"
#include "test_world.h"

namespace arbor::tracer {
namespace {

// Mountains of 400 m relief over 600 m, at 2 m: slopes past 60° on the ridges; the square alone
// (seen from below: the surround's sunk cells would hide it; TerrainWorld.TheSurround* test it).
const char* const kMountains =
    "[terrain]\nkind = \"mountains\"\nsize = 600\nrelief = 400\nresolution = 2\nseed = 3\n"
    "surround = 0\n";

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
  const spec::SceneDesc desc =
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
  const spec::SceneDesc desc = formats::parse_scene(
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
  const spec::SceneDesc desc = formats::parse_scene(terrain, "terrain.toml");
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
    const spec::SceneDesc desc = formats::parse_scene(
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

// The surround meets the square without a gap: rays from above at the seam, from inside and
// outside, at angles from steep to grazing, all meet the terrain, and on its stated surface
// (Terrain::height, within float precision) or on the skirt at the edge, never on the surround's
// cells sunk under the square (a ray through a crack would). Mountains of 400 m relief, whose
// ridges the surround's coarser grid misses most.
TEST(TerrainWorld, TheSurroundMeetsTheSquareWithoutAGap) {
  const spec::SceneDesc desc = formats::parse_scene(
      "[terrain]\nkind = \"mountains\"\nsize = 600\nrelief = 400\nresolution = 2\nseed = 3\n"
      "[ground]\nenabled = false\n",
      "surround.toml");
  const EmbreeDevice device;
  const TestWorld w(desc, device);
  const scene::Terrain& t = w.scene->terrain;
  ASSERT_NE(t.surround(), nullptr);
  Rng rng(11);
  int skirt = 0, surface = 0, below = 0, missed = 0;
  for (int k = 0; k < 20000; ++k) {
    // A point on the seam (one of the four edges), and a ray to it from above, from any side.
    const double u = -300.0 + 600.0 * rng.uniform(), off = -3.0 + 6.0 * rng.uniform();
    const int side = static_cast<int>(4.0 * rng.uniform());
    const double e = 300.0 + off;
    const double x = side == 0 ? u : side == 1 ? e : side == 2 ? -u : -e;
    const double y = side == 0 ? e : side == 1 ? -u : side == 2 ? -e : u;
    const double elevation = (2.0 + 80.0 * rng.uniform()) * 3.14159265358979 / 180.0;
    const double azimuth = 2.0 * 3.14159265358979 * rng.uniform();
    const glm::vec3 to(static_cast<float>(std::cos(elevation) * std::cos(azimuth)),
                       static_cast<float>(std::cos(elevation) * std::sin(azimuth)),
                       static_cast<float>(std::sin(elevation)));
    const glm::vec3 target(static_cast<float>(x), static_cast<float>(y),
                           static_cast<float>(t.height(x, y)));
    Ray ray;
    ray.origin = target + 500.0f * to;
    ray.direction = -to;
    // From above the ground (a grazing ray's start can be inside a mountain in front of it).
    if (ray.origin.z < t.height(ray.origin.x, ray.origin.y) + 1.0) {
      --k;
      continue;
    }
    WorldHit hit;
    if (!w.world.intersect(ray, hit)) {
      ++missed;
      continue;
    }
    const glm::vec3 p = hit.surface.position;
    const bool at_edge = std::abs(std::max(std::abs(p.x), std::abs(p.y)) - 300.0f) < 1e-2f;
    if (at_edge && std::abs(hit.surface.shading_normal.z) < 1e-3f) {
      ++skirt;
      const double ex = std::clamp(static_cast<double>(p.x), -299.9999, 299.9999);
      const double ey = std::clamp(static_cast<double>(p.y), -299.9999, 299.9999);
      EXPECT_LE(p.z, t.height(ex, ey) + 1e-2);  // under the square's edge
    } else if (p.z >= t.height(p.x, p.y) - 1e-2) {
      ++surface;
    } else {
      ++below;
    }
  }
  EXPECT_EQ(missed, 0);
  EXPECT_EQ(below, 0);
  EXPECT_GT(skirt, 0);  // the seam is there to be closed
  EXPECT_GT(surface, 19000);
}

// The ground plane reaches the horizon: seen from 2 km up, a ray a degree below the horizon meets
// it 115 km out, past its 10 km quad (it used to escape, a black band under the sky), and is
// occluded there; a ray above the horizon escapes. With a terrain, at the plane's level under it.
TEST(TerrainWorld, TheGroundPlaneReachesTheHorizon) {
  for (const char* terrain : {"", "[terrain]\nkind = \"hills\"\nsize = 200\nrelief = 20\n"}) {
    SCOPED_TRACE(terrain);
    const spec::SceneDesc desc = formats::parse_scene(terrain, "plane.toml");
    const EmbreeDevice device;
    const TestWorld w(desc, device);
    const float level =
        static_cast<float>(w.scene->terrain.empty() ? 0.0 : w.scene->terrain.floor());
    Ray ray;
    ray.origin = glm::vec3(0.0f, 0.0f, 2000.0f);
    const float down = 1.0f * 3.14159265f / 180.0f;
    ray.direction = glm::vec3(std::cos(down), 0.0f, -std::sin(down));
    WorldHit hit;
    ASSERT_TRUE(w.world.intersect(ray, hit));
    EXPECT_TRUE(hit.ground);
    EXPECT_NEAR(hit.surface.t, (2000.0f - level) / std::sin(down), 10.0f);
    EXPECT_GT(hit.surface.position.x, 1e5f);
    EXPECT_NEAR(hit.surface.position.z, level, 0.01f);
    EXPECT_TRUE(w.world.occluded(ray));
    Ray shorter = ray;
    shorter.t_max = 50000.0f;  // a shadow ray that ends before the plane is not occluded by it
    EXPECT_FALSE(w.world.occluded(shorter));
    ray.direction.z = -ray.direction.z;
    EXPECT_FALSE(w.world.intersect(ray, hit));
    EXPECT_FALSE(w.world.occluded(ray));
  }
}

}  // namespace
}  // namespace arbor::tracer
