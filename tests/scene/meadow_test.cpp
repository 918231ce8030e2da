// Tests of the meadow's blades (scene/meadow.h): as many as the density says, none when it is 0,
// tiles covering the area and nothing beyond, lengths and their spread as documented, tufts when
// clumped, the dry share, above the ground, deterministic by the seed; and the grass's BSDF: its
// sampling against its pdf (χ²) and its energy, for every kind of blade.
#include "scene/meadow.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "../materials/chi_square.h"
#include "common/rng.h"

namespace arbor::scene {
namespace {

spec::MeadowDesc small_meadow(double density) {
  spec::MeadowDesc d;
  d.density = density;
  d.area = {-2.0, -1.0, 2.0, 1.0};
  return d;
}

glm::vec3 bezier(const glm::vec4* p, float u) {
  const float s = 1.0f - u;
  return s * s * s * glm::vec3(p[0]) + 3.0f * s * s * u * glm::vec3(p[1]) +
         3.0f * s * u * u * glm::vec3(p[2]) + u * u * u * glm::vec3(p[3]);
}

double arc_length(const glm::vec4* p) {
  double l = 0.0;
  for (int i = 0; i < 64; ++i) l += glm::length(bezier(p, (i + 1) / 64.0f) - bezier(p, i / 64.0f));
  return l;
}

TEST(Meadow, EachTileHoldsTheDensitysBladesOnAverage) {
  spec::MeadowDesc d = small_meadow(1234.5);
  d.tiles = 16;
  const Meadow m = grow_meadow(d, 0.0);
  ASSERT_EQ(m.tiles.size(), 16u);
  double total = 0.0;
  for (const GrassTile& t : m.tiles) {
    // floor(1234.5) or one more: the mean is exact, each tile within one blade of it.
    EXPECT_GE(t.blades(), 1234u);
    EXPECT_LE(t.blades(), 1235u);
    EXPECT_EQ(t.points.size(), 4 * t.blades());
    EXPECT_EQ(t.normals.size(), 4 * t.blades());
    total += static_cast<double>(t.blades());
  }
  EXPECT_NEAR(total / 16.0, 1234.5, 0.5);
  // 4 × 2 m at 1 m tiles: 8 cells, so 8 placements and about 8 × 1234.5 blades placed.
  EXPECT_EQ(m.placements.size(), 8u);
  EXPECT_NEAR(static_cast<double>(m.placed_blades()), 8 * 1234.5, 8.0);
}

TEST(Meadow, ZeroDensityGrowsNothing) {
  const Meadow m = grow_meadow(small_meadow(0.0), 0.0);
  EXPECT_TRUE(m.empty());
  EXPECT_TRUE(m.tiles.empty());
  EXPECT_EQ(m.placed_blades(), 0u);
  // A density below one blade a tile leaves most tiles empty, and empty tiles are not placed.
  spec::MeadowDesc sparse = small_meadow(0.2);
  sparse.tiles = 64;
  sparse.area = {-10.0, -10.0, 10.0, 10.0};
  const Meadow s = grow_meadow(sparse, 0.0);
  for (const GrassPlacement& p : s.placements)
    EXPECT_GT(s.tiles[static_cast<std::size_t>(p.tile)].blades(), 0u);
  // Each cell takes one of the 64 tiles: the placed share follows the tiles that hold a blade.
  double holding = 0.0;
  for (const GrassTile& t : s.tiles) holding += static_cast<double>(t.blades()) / 64.0;
  EXPECT_NEAR(holding, 0.2, 0.15);
  EXPECT_NEAR(static_cast<double>(s.placed_blades()) / 400.0, holding, 0.07);
}

TEST(Meadow, TilesCoverTheAreaRoundedOutAndNothingBeyond) {
  spec::MeadowDesc d = small_meadow(50.0);
  d.area = {-1.5, 0.25, 1.2, 2.0};
  d.tile = 0.5;
  const Meadow m = grow_meadow(d, 0.0);
  // Cells from floor(x0 / tile) to ceil(x1 / tile): x in [-1.5, 1.5), y in [0, 2).
  EXPECT_EQ(m.placements.size(), 6u * 4u);
  for (const GrassPlacement& p : m.placements) {
    const GrassTile& t = m.tiles[static_cast<std::size_t>(p.tile)];
    for (std::size_t i = 0; i < t.blades(); ++i) {
      const glm::vec3 root = glm::vec3(p.to_world * glm::vec4(glm::vec3(t.points[4 * i]), 1.0f));
      EXPECT_GE(root.x, -1.5f - 1e-5f);
      EXPECT_LE(root.x, 1.5f + 1e-5f);
      EXPECT_GE(root.y, 0.0f - 1e-5f);
      EXPECT_LE(root.y, 2.0f + 1e-5f);
    }
  }
}

TEST(Meadow, BladeLengthsHaveTheDocumentedMedianAndSpread) {
  spec::MeadowDesc d = small_meadow(3000.0);
  d.height = 0.4;
  d.height_spread = 0.25;
  const GrassTile t = grow_grass_tile(d, 0, 0.0);
  std::vector<double> ln;
  for (std::size_t i = 0; i < t.blades(); ++i) ln.push_back(std::log(arc_length(&t.points[4 * i])));
  std::sort(ln.begin(), ln.end());
  const double median = std::exp(ln[ln.size() / 2]);
  const double mean = std::accumulate(ln.begin(), ln.end(), 0.0) / static_cast<double>(ln.size());
  double var = 0.0;
  for (const double x : ln) var += (x - mean) * (x - mean);
  const double sigma = std::sqrt(var / static_cast<double>(ln.size() - 1));
  EXPECT_NEAR(median, 0.4, 0.4 * 0.03);
  EXPECT_NEAR(sigma, 0.25, 0.02);
}

TEST(Meadow, BladesStayAboveTheGroundAndTaperToTheTip) {
  spec::MeadowDesc d = small_meadow(2000.0);
  d.lean = 60.0;
  d.bend = 1.0;
  d.wind = 20.0;
  const GrassTile t = grow_grass_tile(d, 1, 0.0);
  for (std::size_t i = 0; i < t.blades(); ++i) {
    const glm::vec4* p = &t.points[4 * i];
    for (int k = 0; k <= 32; ++k) ASSERT_GE(bezier(p, k / 32.0f).z, -0.0051f) << i;
    EXPECT_LT(p[3].w, 0.05f * p[0].w);
    EXPECT_GT(bezier(p, 1.0f).z, 0.0f);
  }
}

// Clark and Evans's ratio: the mean distance to the nearest other root over its value for
// uniformly random points, 1/(2 √density). Torus distances: the tile repeats.
double clark_evans(const GrassTile& t, double side, double density) {
  double sum = 0.0;
  const std::size_t n = std::min<std::size_t>(t.blades(), 600);
  for (std::size_t i = 0; i < n; ++i) {
    double best = 1e9;
    for (std::size_t j = 0; j < t.blades(); ++j) {
      if (i == j) continue;
      double dx = std::fabs(t.points[4 * i].x - t.points[4 * j].x);
      double dy = std::fabs(t.points[4 * i].y - t.points[4 * j].y);
      dx = std::min(dx, side - dx);
      dy = std::min(dy, side - dy);
      best = std::min(best, std::sqrt(dx * dx + dy * dy));
    }
    sum += best;
  }
  return sum / static_cast<double>(n) * 2.0 * std::sqrt(density);
}

TEST(Meadow, ClumpingGathersBladesIntoTufts) {
  spec::MeadowDesc d = small_meadow(400.0);
  d.clumping = 0.0;
  const double uniform = clark_evans(grow_grass_tile(d, 0, 0.0), d.tile, d.density);
  d.clumping = 0.9;
  const double clumped = clark_evans(grow_grass_tile(d, 0, 0.0), d.tile, d.density);
  EXPECT_NEAR(uniform, 1.0, 0.08);
  EXPECT_LT(clumped, 0.6);
}

TEST(Meadow, TheDryShareIsStrawColoured) {
  spec::MeadowDesc d = small_meadow(5000.0);
  d.dry = 0.2;
  const GrassTile t = grow_grass_tile(d, 2, 0.0);
  std::size_t dry = 0;
  for (const glm::vec3& c : t.colors) dry += c != glm::vec3(1.0f);
  const double share = static_cast<double>(dry) / static_cast<double>(t.blades());
  EXPECT_NEAR(share, 0.2, 3.0 * std::sqrt(0.2 * 0.8 / static_cast<double>(t.blades())));
}

TEST(Meadow, IsAFunctionOfItsTableAndClock) {
  const spec::MeadowDesc d = small_meadow(500.0);
  const GrassTile a = grow_grass_tile(d, 3, 0.0), b = grow_grass_tile(d, 3, 0.0);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.normals, b.normals);
  spec::MeadowDesc other = d;
  other.seed = 2;
  EXPECT_NE(grow_grass_tile(other, 3, 0.0).points, a.points);
  // The wind sways the blades over time; in calm air the clock changes nothing.
  spec::MeadowDesc windy = d;
  windy.wind = 5.0;
  EXPECT_NE(grow_grass_tile(windy, 3, 0.0).points, grow_grass_tile(windy, 3, 0.3).points);
  EXPECT_EQ(grow_grass_tile(d, 3, 0.3).points, a.points);
}

// Every kind of blade — green and dry, seen from above and below, each its own tint — samples
// its own pdf (χ²) and reflects plus transmits at most what comes in.
TEST(GrassBsdf, SamplesItsPdfAndCreatesNoEnergy) {
  spec::MeadowDesc d = small_meadow(100.0);
  d.dry = 0.5;
  const Meadow m = grow_meadow(d, 0.0);
  const materials::LeafMaterial* grass = m.grass.as<materials::LeafMaterial>();
  ASSERT_NE(grass, nullptr);
  EXPECT_EQ(grass->cuticle, nullptr);
  const GrassTile& t = m.tiles[0];
  int checked = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    for (const bool back : {false, true}) {
      materials::SurfacePoint p;
      p.shading_normal = p.geometric_normal = {0.0f, 0.0f, 1.0f};
      p.leaf_back = back;
      p.color = t.colors[i];
      p.leaf_key = derive_key(99, i);
      p.crown_height = 0.5f;
      const materials::SurfaceBsdf b = m.grass.bsdf(p);
      ASSERT_TRUE(b.transmits());
      const auto& lobe = std::get<materials::LeafBsdf>(b.lobes);
      for (int c = 0; c < 3; ++c) EXPECT_LE(lobe.reflectance[c] + lobe.transmittance[c], 1.0);
      const glm::dvec3 wo = glm::normalize(glm::dvec3(0.3, -0.2, 0.8));
      const auto r = materials::testing::chi_square(
          [&](Rng& rng) {
            return lobe.sample(wo, {rng.uniform(), rng.uniform(), rng.uniform()});
          },
          [&](const glm::dvec3& wi) { return lobe.pdf(wo, wi); }, 40000, 7 + i);
      EXPECT_LT(r.chi2, materials::testing::chi_square_critical(r.degrees_of_freedom));
      // The white furnace of one bounce: ∫ f |cos| dω over the sphere is R + T ≤ 1.
      Rng rng(5 + i);
      glm::dvec3 sum(0.0);
      const int n = 20000;
      for (int k = 0; k < n; ++k) {
        const materials::BsdfSample s =
            lobe.sample(wo, {rng.uniform(), rng.uniform(), rng.uniform()});
        sum += s.value * std::fabs(s.wi.z) / s.pdf / double(n);
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sum[c], lobe.reflectance[c] + lobe.transmittance[c], 0.01);
        EXPECT_LE(sum[c], 1.0 + 0.01);
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 12);
}

}  // namespace
}  // namespace arbor::scene
