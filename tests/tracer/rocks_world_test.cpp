// Tests of the rocks in the Embree world: a ray straight down each rock's axis meets the rock
// above the terrain (its object and material ids, all-rock cover, normals facing the ray, the
// point on the placed shape), and beside the rocks it meets the terrain.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "formats/scene_file.h"
#include "test_world.h"

namespace arbor::tracer {
namespace {

TEST(RocksWorld, RaysDownMeetEachRockAndTheTerrainBeside) {
  const spec::SceneDesc desc = formats::parse_scene(
      "[terrain]\nkind = \"mountains\"\nsize = 100\nrelief = 30\nresolution = 1\nseed = 5\n"
      "[rocks]\ndensity = 0.05\nsize_min = 0.5\nsize_max = 2\n",
      "rocks.toml");
  const EmbreeDevice device;
  const TestWorld w(desc, device);
  const scene::Rocks& rocks = w.scene->rocks;
  ASSERT_GT(rocks.placements.size(), 20u);
  ASSERT_NE(rocks.object_id, 0u);
  int on_rock = 0;
  for (const scene::RockPlacement& p : rocks.placements) {
    const scene::RockShape& s = rocks.shapes[static_cast<std::size_t>(p.shape)];
    // Down the rock's axis: the rock, above the terrain there.
    const glm::vec3 top(p.to_world * glm::vec4(0.0f, 0.0f, s.top, 1.0f));
    Ray ray;
    ray.origin = glm::vec3(top.x, top.y, top.z + 50.0f);
    ray.direction = glm::vec3(0, 0, -1);
    WorldHit hit;
    ASSERT_TRUE(w.world.intersect(ray, hit));
    EXPECT_EQ(hit.object_id, rocks.object_id)
        << "above a rock of " << p.diameter << " m at " << top.x << ", " << top.y << ", " << top.z
        << ": " << (hit.ground ? "the terrain" : "something") << " at z " << hit.surface.position.z;
    if (hit.object_id != rocks.object_id) continue;
    ++on_rock;
    EXPECT_GT(hit.surface.position.z, w.scene->terrain.height(top.x, top.y));
    EXPECT_LT(hit.surface.position.z, top.z + 0.5f * p.diameter);
    EXPECT_EQ(hit.material_id, rocks.material_id);
    EXPECT_EQ(hit.surface.terrain, glm::vec2(0.0f, 1.0f));
    EXPECT_LT(glm::dot(hit.surface.geometric_normal, ray.direction), 0.0f);
    EXPECT_LT(glm::dot(hit.surface.shading_normal, ray.direction), 0.0f);
    // Two rock diameters beside it (away from any other rock there), the terrain.
    Ray beside = ray;
    beside.origin.x += 2.0f * p.diameter + 0.5f;
    WorldHit ground;
    ASSERT_TRUE(w.world.intersect(beside, ground));
    if (ground.object_id != rocks.object_id) {
      EXPECT_TRUE(ground.ground);
      EXPECT_NEAR(ground.surface.position.z,
                  w.scene->terrain.height(beside.origin.x, beside.origin.y), 2e-3);
    }
  }
  EXPECT_GE(on_rock, static_cast<int>(rocks.placements.size()) * 9 / 10);
}

}  // namespace
}  // namespace arbor::tracer
