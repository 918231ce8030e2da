// Tests of a meadow on a terrain (scene/meadow.h, grow_meadow with a terrain): on the steepest
// mountains arbor ships, every blade is rooted on the rendered surface (5 mm into it, as on the
// plane) and all but a few at creases stand out of it; the blades thin out by the ground's cover to
// the documented share on average, with none on bare rock; and the placements are a function of the
// tables.
#include <cmath>
#include <cstddef>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "scene/meadow.h"

namespace arbor::scene {
namespace {

// Ridged mountains, 160 m across on a 4 m grid with 120 m of relief: faces over 60°.
Terrain steep_mountains() {
  spec::TerrainDesc t;
  t.enabled = true;
  t.kind = spec::TerrainKind::Mountains;
  t.size = 160;
  t.resolution = 4;
  t.relief = 120;
  t.seed = 3;
  t.surround = 0;  // the square alone: its blades
  return Terrain(t);
}

spec::MeadowDesc meadow_on(const Terrain& terrain, double density) {
  spec::MeadowDesc d;
  d.density = density;
  d.tile = terrain.spacing();
  d.area = {-80.0, -80.0, 80.0, 80.0};
  return d;
}

glm::vec3 world(const GrassPlacement& p, const glm::vec4& local) {
  return glm::vec3(p.to_world * glm::vec4(glm::vec3(local), 1.0f));
}

TEST(MeadowOnTerrain, EveryBladeIsRootedOnTheSurfaceAndStandsOutOfIt) {
  const Terrain terrain = steep_mountains();
  double steepest = 0.0;
  for (double y = -78.0; y < 78.0; y += 2.0)
    for (double x = -78.0; x < 78.0; x += 2.0) steepest = std::max(steepest, terrain.slope(x, y));
  ASSERT_GT(steepest, 60.0);
  const Meadow m = grow_meadow(meadow_on(terrain, 100.0), 0.0, terrain);
  std::size_t blades = 0, tips_above = 0;
  double worst = 0.0;
  for (const GrassPlacement& p : m.placements) {
    const GrassTile& tile = m.tiles[static_cast<std::size_t>(p.tile)];
    for (std::size_t b = 0; b < tile.blades(); ++b) {
      const glm::vec3 root = world(p, tile.points[GrassTile::kPointsPerBlade * b]);
      const glm::vec3 tip = world(p, tile.points[GrassTile::kPointsPerBlade * b + 3]);
      worst = std::max(worst, std::abs(root.z + 0.005 - terrain.height(root.x, root.y)));
      tips_above += tip.z > terrain.height(tip.x, tip.y) + 0.01;
      ++blades;
    }
  }
  ASSERT_GT(blades, 20000u);
  EXPECT_LT(worst, 1e-3) << "a root off the surface by " << worst << " m";
  // A blade leaning across a concave crease can touch the next face (docs/landscape.md): on these
  // mountains 0.2 % do.
  EXPECT_GT(static_cast<double>(tips_above), 0.995 * static_cast<double>(blades));
}

TEST(MeadowOnTerrain, BladesThinOutByTheCoverAndNoneGrowOnRock) {
  const Terrain terrain = steep_mountains();
  const double density = 100.0, s = terrain.spacing();
  const Meadow m = grow_meadow(meadow_on(terrain, density), 0.0, terrain);
  double placed = 0.0, expected = 0.0, on_rock = 0.0;
  for (const GrassPlacement& p : m.placements) {
    const GrassTile& tile = m.tiles[static_cast<std::size_t>(p.tile)];
    if (tile.blades() == 0) continue;
    for (std::size_t b = 0; b < tile.blades(); ++b) {
      const glm::vec3 root = world(p, tile.points[GrassTile::kPointsPerBlade * b]);
      on_rock += terrain.cover(root.x, root.y).y > 0.9f;
    }
    placed += static_cast<double>(tile.blades());
  }
  // Every triangle's expected blades by its share of grass.
  for (int j = 0; j + 1 < terrain.rows(); ++j)
    for (int i = 0; i + 1 < terrain.columns(); ++i)
      for (const int upper : {0, 1})
        expected += 0.5 * s * s * density * triangle_grass_share(terrain, i, j, upper);
  ASSERT_GT(expected, 20000.0);
  EXPECT_NEAR(placed / expected, 1.0, 0.03);
  EXPECT_LT(on_rock, 0.01 * placed) << on_rock << " of " << placed << " on rock";
  EXPECT_LT(placed, 0.9 * density * 160.0 * 160.0) << "the rock took nothing away";
}

TEST(MeadowOnTerrain, GrassShareIsAllOnMeadowNoneOnRockAndLittleOnSoil) {
  EXPECT_EQ(grass_share({0.0f, 0.0f}), 1.0);
  EXPECT_EQ(grass_share({0.0f, 1.0f}), 0.0);
  EXPECT_NEAR(grass_share({1.0f, 0.0f}), 0.3, 1e-9);
}

TEST(MeadowOnTerrain, IsAFunctionOfItsTables) {
  const Terrain terrain = steep_mountains();
  const Meadow a = grow_meadow(meadow_on(terrain, 1.0), 0.0, terrain);
  const Meadow b = grow_meadow(meadow_on(terrain, 1.0), 0.0, terrain);
  ASSERT_EQ(a.placements.size(), b.placements.size());
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    ASSERT_EQ(a.placements[i].tile, b.placements[i].tile);
    ASSERT_EQ(a.placements[i].to_world, b.placements[i].to_world);
  }
}

}  // namespace
}  // namespace arbor::scene
