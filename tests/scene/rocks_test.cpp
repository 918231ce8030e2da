// Tests of the rocks (scene/rocks.h): on the steepest mountains arbor ships no rock floats (the
// bottom of each is under the ground all round), their diameters follow the stated power law,
// they lie on rock and scree by the stated shares, and they are a function of the table.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "scene/rocks.h"

namespace arbor::scene {
namespace {

// Ridged mountains, 160 m across on a 2 m grid with 120 m of relief: faces over 60°.
Terrain steep_mountains(double relief = 120) {
  spec::TerrainDesc t;
  t.enabled = true;
  t.kind = spec::TerrainKind::Mountains;
  t.size = 160;
  t.resolution = 2;
  t.relief = relief;
  t.seed = 3;
  t.surround = 0;  // the square alone, whose edges fall to its lowest level
  return Terrain(t);
}

spec::RocksDesc rocks_desc(double density) {
  spec::RocksDesc d;
  d.enabled = true;
  d.density = density;
  return d;
}

glm::vec3 world(const RockPlacement& p, const glm::vec3& local) {
  return glm::vec3(p.to_world * glm::vec4(local, 1.0f));
}

// Every vertex in the bottom tenth of a rock's height is under the terrain: the rock sits in
// the ground all round its base, on the downhill side too, so none floats.
TEST(Rocks, NoneFloatsOnTheSteepestMountains) {
  const Terrain terrain = steep_mountains();
  const Rocks rocks = place_rocks(rocks_desc(0.5), terrain);
  ASSERT_GT(rocks.placements.size(), 250u);
  double steepest = 0.0;
  std::size_t vertices = 0;
  for (const RockPlacement& p : rocks.placements) {
    const RockShape& s = rocks.shapes[static_cast<std::size_t>(p.shape)];
    steepest = std::max(steepest, terrain.slope(p.to_world[3].x, p.to_world[3].y));
    const float cut = s.bottom + 0.1f * (s.top - s.bottom);
    for (const glm::vec3& v : s.positions) {
      if (v.z > cut) continue;
      const glm::vec3 w = world(p, v);
      ASSERT_LT(w.z, terrain.height(w.x, w.y)) << "a rock of " << p.diameter << " m floats";
      ++vertices;
    }
    // And it shows: a tenth of its surface at least is out of the ground (none is buried).
    std::size_t out = 0;
    for (const glm::vec3& v : s.positions) {
      const glm::vec3 w = world(p, v);
      if (w.z > terrain.height(w.x, w.y)) ++out;
    }
    EXPECT_GT(out, s.positions.size() / 10) << "a rock of " << p.diameter << " m is buried";
  }
  EXPECT_GT(steepest, 40.0);
  EXPECT_GT(vertices, rocks.placements.size() * 10);
}

// The diameters follow the truncated power law: Kolmogorov–Smirnov against its CDF at the 1 %
// level, and against a law of exponent 2.2 they are refused.
TEST(Rocks, TheirSizesFollowThePowerLaw) {
  spec::RocksDesc d = rocks_desc(0.5);
  d.size_min = 0.2;
  d.size_max = 4.0;
  d.exponent = 2.5;
  spec::RocksDesc flat = d;
  flat.area = std::array<double, 4>{-40.0, -40.0, 40.0, 40.0};
  const Rocks rocks = place_rocks(flat, Terrain{});
  ASSERT_GT(rocks.placements.size(), 2000u);
  std::vector<double> sizes;
  for (const RockPlacement& p : rocks.placements) sizes.push_back(p.diameter);
  std::sort(sizes.begin(), sizes.end());
  auto ks = [&](double exponent) {
    const double e = 1.0 - exponent, a = std::pow(d.size_min, e), b = std::pow(d.size_max, e);
    double worst = 0.0;
    const double n = static_cast<double>(sizes.size());
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      const double cdf = (std::pow(sizes[i], e) - a) / (b - a);
      worst = std::max({worst, std::abs(cdf - i / n), std::abs(cdf - (i + 1) / n)});
    }
    return worst * std::sqrt(n);
  };
  EXPECT_LT(ks(2.5), 1.63);  // the 1 % critical value
  EXPECT_GT(ks(2.2), 1.63);
  EXPECT_GE(sizes.front(), d.size_min);
  EXPECT_LE(sizes.back(), d.size_max);
}

// Rocks lie where the ground is rock at the table's density, at half of it on the soil below
// (scree), and at a twentieth elsewhere, on slopes up to 45° (measured over gentler mountains'
// cover); fewer where the ground under a rock is too rough for it to rest.
TEST(Rocks, LieOnRockAndScreeByTheirShares) {
  const Terrain terrain = steep_mountains(40);
  const Rocks rocks = place_rocks(rocks_desc(0.2), terrain);
  // The area of each kind of ground, on a 0.5 m grid, and the rocks on each.
  double rock_area = 0.0, meadow_area = 0.0, scree_area = 0.0;
  for (double y = -80.0; y < 80.0; y += 0.5)
    for (double x = -80.0; x < 80.0; x += 0.5) {
      const glm::vec2 c = terrain.cover(x, y);
      if (terrain.slope(x, y) > 45.0) continue;
      if (c.y >= 0.99f) rock_area += 0.25;
      if (c.x >= 0.99f && c.y <= 0.01f) scree_area += 0.25;
      if (c.x <= 0.01f && c.y <= 0.01f) meadow_area += 0.25;
    }
  double on_rock = 0.0, on_meadow = 0.0, on_scree = 0.0;
  for (const RockPlacement& p : rocks.placements) {
    const glm::vec2 c = terrain.cover(p.to_world[3].x, p.to_world[3].y);
    if (c.y >= 0.99f) ++on_rock;
    if (c.x >= 0.99f && c.y <= 0.01f) ++on_scree;
    if (c.x <= 0.01f && c.y <= 0.01f) ++on_meadow;
  }
  ASSERT_GT(rock_area, 1000.0);
  ASSERT_GT(meadow_area, 1000.0);
  // Fewer on rock crests rougher than 0.4 of a rock's height under it: 25 % fewer here (measured).
  EXPECT_LT(on_rock / rock_area, 0.2 * 1.05);
  EXPECT_GT(on_rock / rock_area, 0.2 * 0.7);
  EXPECT_NEAR(on_meadow / meadow_area, 0.01, 0.01 * 0.25);
  ASSERT_GT(scree_area, 200.0);
  EXPECT_NEAR(on_scree / scree_area, 0.1, 0.1 * 0.3);
}

TEST(Rocks, AreAFunctionOfTheirTable) {
  const Terrain terrain = steep_mountains();
  const Rocks a = place_rocks(rocks_desc(0.02), terrain),
              b = place_rocks(rocks_desc(0.02), terrain);
  ASSERT_EQ(a.placements.size(), b.placements.size());
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    EXPECT_EQ(a.placements[i].to_world, b.placements[i].to_world);
    EXPECT_EQ(a.placements[i].shape, b.placements[i].shape);
  }
  spec::RocksDesc other = rocks_desc(0.02);
  other.seed = 2;
  EXPECT_NE(place_rocks(other, terrain).placements.front().to_world, a.placements.front().to_world);
}

}  // namespace
}  // namespace arbor::scene
