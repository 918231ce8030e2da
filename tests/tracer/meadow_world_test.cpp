// Tests of the meadow in the Embree world: rays straight down find blades inside the meadow's
// area as often as its density says (doubling the density is two independent layers of cover),
// the bare ground beyond it and everywhere when the density is 0; blade hits are two-sided
// leaves of the meadow's material, facing the ray, their upper face seen from above.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/math.h"
#include "common/rng.h"
#include "formats/scene_file.h"
#include "test_world.h"
#include "tracer/integrators/path.h"

namespace arbor::tracer {
namespace {

struct Cover {
  double inside = 0.0, outside = 0.0;  // the share of vertical rays that meet a blade
  double predicted = 0.0;              // the share inside, from the blades' projected areas
  int front = 0, back = 0;
};

// The area a tile's blades cover seen from above, by the ribbons' own definition and not by
// Embree: the ribbon at C(s) spans ±r(s) along a = n × C′ (normalised), so it covers
// ∫ 2 r |(C′ × a)_z| ds of the ground (its own overlaps neglected).
double projected_area(const scene::GrassTile& t) {
  double area = 0.0;
  for (std::size_t b = 0; b < t.blades(); ++b) {
    const glm::vec4* p = &t.points[4 * b];
    const glm::vec3* n = &t.normals[4 * b];
    const int steps = 64;
    for (int i = 0; i < steps; ++i) {
      const float u = (static_cast<float>(i) + 0.5f) / steps, s = 1.0f - u;
      const float w[4] = {s * s * s, 3 * s * s * u, 3 * s * u * u, u * u * u};
      const glm::vec3 d =
          3.0f * (s * s * glm::vec3(p[1] - p[0]) + 2.0f * s * u * glm::vec3(p[2] - p[1]) +
                  u * u * glm::vec3(p[3] - p[2]));
      glm::vec3 normal(0.0f);
      float r = 0.0f;
      for (int k = 0; k < 4; ++k) {
        normal += w[k] * n[k];
        r += w[k] * p[k].w;
      }
      const glm::vec3 a = glm::normalize(glm::cross(normal, d));
      area += 2.0 * r * std::fabs(glm::cross(d, a).z) / steps;
    }
  }
  return area;
}

void cover(double density, std::uint64_t seed, Cover& c) {
  spec::SceneDesc desc = formats::parse_scene(
      "[meadow]\ndensity = " + std::to_string(density) +
          "\narea = [[-3.0, -3.0], [3.0, 3.0]]\nclumping = 0.0\nseed = " + std::to_string(seed) +
          "\n",
      "meadow.toml");
  const EmbreeDevice device;
  const TestWorld w(desc, device);
  Rng rng(11);
  // Blades placed independently and uniformly in a tile leave the ground bare with probability
  // exp(−their projected area / the tile's), averaged over the cells the rays sample.
  const scene::Meadow& m = w.scene->meadow;
  int cells = 0;
  for (const scene::GrassPlacement& p : m.placements) {
    const glm::vec3 centre = glm::vec3(p.to_world * glm::vec4(0.5f, 0.5f, 0.0f, 1.0f));
    if (std::fabs(centre.x) > 2.5f || std::fabs(centre.y) > 2.5f) continue;
    c.predicted += 1.0 - std::exp(-projected_area(m.tiles[static_cast<std::size_t>(p.tile)]));
    ++cells;
  }
  if (cells > 0) c.predicted /= cells;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    for (const bool inside : {true, false}) {
      Ray ray;
      // Inside: the middle 5 × 5 m; outside: a band 1–4 m beyond the meadow's edge.
      const double x =
          inside ? rng.vary(0.0, 2.5) : rng.vary(0.0, 2.5) + (rng.uniform() < 0.5 ? -6.5 : 6.5);
      const double y = rng.vary(0.0, inside ? 2.5 : 7.0);
      ray.origin = glm::vec3(static_cast<float>(x), static_cast<float>(y), 3.0f);
      ray.direction = glm::vec3(0.0f, 0.0f, -1.0f);
      WorldHit hit;
      ASSERT_TRUE(w.world.intersect(ray, hit));
      if (hit.ground) continue;
      EXPECT_GE(hit.grass, 0);
      EXPECT_EQ(hit.instance, -1);
      EXPECT_EQ(hit.surface.kind, SurfaceKind::Leaf);
      EXPECT_EQ(hit.material, &w.scene->meadow.grass);
      EXPECT_LT(glm::dot(hit.surface.geometric_normal, ray.direction), 0.0f);
      EXPECT_EQ(hit.surface.material, generator::kMaterialLeafFront);  // the upper face
      (inside ? c.inside : c.outside) += 1.0 / n;
    }
    // Across the meadow, 5 cm above the ground: both faces of the leaning blades are met.
    Ray across;
    const double a = 2.0 * kPi * rng.uniform();
    across.origin = glm::vec3(static_cast<float>(rng.vary(0.0, 2.0)),
                              static_cast<float>(rng.vary(0.0, 2.0)), 0.05f);
    across.direction =
        glm::vec3(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
    WorldHit hit;
    if (w.world.intersect(across, hit) && hit.grass >= 0) {
      EXPECT_LT(glm::dot(hit.surface.geometric_normal, across.direction), 0.0f);
      (hit.surface.material == generator::kMaterialLeafBack ? c.back : c.front) += 1;
    }
  }
}

TEST(MeadowWorld, BladesCoverTheAreaAsTheDensitySaysAndNothingBeyond) {
  Cover none, one, two;
  cover(0.0, 1, none);
  cover(3000.0, 1, one);
  cover(6000.0, 2, two);
  EXPECT_EQ(none.inside, 0.0);
  EXPECT_EQ(one.outside, 0.0);
  EXPECT_EQ(two.outside, 0.0);
  EXPECT_GT(one.inside, 0.3);
  EXPECT_LT(one.inside, 0.7);
  EXPECT_NEAR(one.inside, one.predicted, 0.02);
  EXPECT_NEAR(two.inside, two.predicted, 0.02);
  // Blades scattered independently: the ground stays bare with probability (1 − f)² at twice
  // the density. σ of each share ≈ 0.0035; the tiles repeat, so allow a little more.
  EXPECT_NEAR(1.0 - two.inside, (1.0 - one.inside) * (1.0 - one.inside), 0.02)
      << one.inside << " " << two.inside;
  // From the side, about as many lower faces as upper ones.
  EXPECT_GT(one.front, 2000);
  EXPECT_GT(one.back, 2000);
}

// Shadow acne on the blades: from every blade a ray meets (over a meadow far from the origin,
// where the offset is largest), a ray leaves in a random direction with the integrator's offset
// rule; none may meet the same blade of the same cell again within a millimetre.
TEST(MeadowWorld, RaysLeavingABladeDoNotHitItAgain) {
  const spec::SceneDesc desc = formats::parse_scene(
      "[meadow]\ndensity = 3000\narea = [[140.0, -90.0], [146.0, -84.0]]\n", "meadow.toml");
  const EmbreeDevice device("threads=1");
  const TestWorld w(desc, device);
  Rng rng(23);
  int hits = 0, acne = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray ray;
    const double a = 2.0 * kPi * rng.uniform();
    ray.origin = glm::vec3(static_cast<float>(143.0 + 1.5 * rng.symmetric()),
                           static_cast<float>(-87.0 + 1.5 * rng.symmetric()), 0.4f);
    ray.direction =
        glm::normalize(glm::vec3(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)),
                                 static_cast<float>(-0.2 - 0.8 * rng.uniform())));
    WorldHit hit;
    if (!w.world.intersect(ray, hit) || hit.grass < 0) continue;
    ++hits;
    const glm::vec3 d = glm::normalize(glm::vec3(static_cast<float>(rng.symmetric()),
                                                 static_cast<float>(rng.symmetric()),
                                                 static_cast<float>(rng.symmetric())));
    const Ray out = spawn_ray(hit.surface.position, hit.surface.geometric_normal, d);
    WorldHit again;
    if (w.world.intersect(out, again) && again.grass == hit.grass &&
        again.surface.primitive == hit.surface.primitive && again.surface.t < 1e-3f) {
      ++acne;
    }
  }
  EXPECT_GT(hits, 10000);
  EXPECT_EQ(acne, 0) << "of " << hits << " hits";
}

}  // namespace
}  // namespace arbor::tracer
