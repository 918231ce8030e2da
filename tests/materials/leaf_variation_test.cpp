// Each leaf's own tint (materials/leaf_variation.h): the distribution's mean and spread against
// the documented values, the crown gradient, determinism, and that a varied leaf never creates
// energy and shows its variation in the albedo AOV.
#include "materials/leaf_variation.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "materials/leaf.h"

namespace arbor::materials {
namespace {

struct Moments {
  double mean = 0.0, sd = 0.0;
};
Moments moments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (double v : x) m.sd += (v - m.mean) * (v - m.mean);
  m.sd = std::sqrt(m.sd / static_cast<double>(x.size() - 1));
  return m;
}

// ln tint_B = σ_v z₁ − σ_v²/2 and ln(tint_R / tint_B) = σ_h z₂ − σ_h²/2, green 0.35 of red's
// chlorophyll part, mean tint 1 in every channel. 40,000 leaves: the means are within 4 standard
// errors, the spreads within 2 % (their standard error is 0.4 %; the ±3 clamp takes 0.3 %).
// Power: drawing ln brightness with σ² as its spread, or leaving out the −σ²/2 that keeps the mean
// at 1, fails it.
TEST(LeafVariation, MeanAndSpreadAreTheDocumentedOnes) {
  const LeafVariation v{0.2f, 0.15f, 0.0f};
  constexpr int kLeaves = 40000;
  std::vector<double> blue, red_over_blue, green_over_blue;
  double mean_tint[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < kLeaves; ++i) {
    const glm::vec3 t = v.tint(derive_key(7, static_cast<std::uint64_t>(i)), 0.5f);
    blue.push_back(std::log(t.b));
    red_over_blue.push_back(std::log(t.r / t.b));
    green_over_blue.push_back(std::log(t.g / t.b));
    for (int c = 0; c < 3; ++c) mean_tint[c] += t[c] / kLeaves;
  }
  const double n = std::sqrt(double(kLeaves));
  const Moments b = moments(blue), r = moments(red_over_blue), g = moments(green_over_blue);
  EXPECT_NEAR(b.mean, -0.5 * 0.2 * 0.2, 4.0 * 0.2 / n);
  EXPECT_NEAR(b.sd / 0.2, 1.0, 0.02);
  EXPECT_NEAR(r.mean, -0.5 * 0.15 * 0.15, 4.0 * 0.15 / n);
  EXPECT_NEAR(r.sd / 0.15, 1.0, 0.02);
  EXPECT_NEAR(g.sd / (0.35 * 0.15), 1.0, 0.02);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean_tint[c], 1.0, 0.006) << "channel " << c;
}

TEST(LeafVariation, CrownGradientLightensTheTopByItsValue) {
  const LeafVariation v{0.2f, 0.1f, 0.4f};
  for (std::uint64_t key : {1ull, 99ull, 123456789ull}) {
    const glm::vec3 top = v.tint(key, 1.0f), bottom = v.tint(key, 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(std::log(top[c] / bottom[c]), 0.4, 1e-5);
  }
}

TEST(LeafVariation, EachLeafHasItsOwnTintAlways) {
  const LeafVariation v{0.2f, 0.1f, 0.0f};
  EXPECT_EQ(v.tint(42, 0.3f), v.tint(42, 0.3f));
  EXPECT_NE(v.tint(42, 0.3f), v.tint(43, 0.3f));
  EXPECT_FALSE(LeafVariation{}.any());
  EXPECT_EQ(LeafVariation{}.tint(42, 0.3f), glm::vec3(1.0f));
}

// A bright leaf varied strongly: reflectance + transmittance stays at most 1 in every channel of
// every leaf, on both sides, keeping its ratio where it is scaled down; and the albedo AOV is the
// varied reflectance. Power: without the scaling, 3,162 of these 30,000 channel values (nearly
// all green) would exceed 1.
TEST(LeafVariation, AVariedLeafNeverCreatesEnergyAndShowsInTheAlbedo) {
  LeafMaterial m;
  m.front = {0.10f, 0.40f, 0.05f};
  m.back = {0.15f, 0.45f, 0.08f};
  m.transmittance = {0.10f, 0.45f, 0.05f};
  m.variation = {0.5f, 0.3f, 0.5f};
  int scaled = 0;
  glm::vec3 first_albedo{0.0f};
  for (int i = 0; i < 5000; ++i) {
    for (bool back : {false, true}) {
      SurfacePoint p;
      p.leaf_back = back;
      p.leaf_key = derive_key(3, static_cast<std::uint64_t>(i));
      p.crown_height = (i % 11) / 10.0f;
      const SurfaceBsdf b = m.bsdf(p);
      const LeafBsdf& l = std::get<LeafBsdf>(b.lobes);
      const glm::vec3 raw = (back ? m.back : m.front) * m.tint(p);
      for (int c = 0; c < 3; ++c) {
        ASSERT_LE(l.reflectance[c] + l.transmittance[c], 1.0 + 1e-12) << i << " " << c;
        if (raw[c] + m.transmittance[c] * m.tint(p)[c] > 1.0f) {
          ++scaled;
          EXPECT_NEAR(l.reflectance[c] / l.transmittance[c],
                      raw[c] / (m.transmittance[c] * m.tint(p)[c]), 1e-5);
        }
      }
      EXPECT_EQ(m.albedo_at(p), glm::vec3(l.reflectance));
      if (i == 0 && !back) first_albedo = m.albedo_at(p);
      if (i == 1 && !back) {
        EXPECT_NE(m.albedo_at(p), first_albedo);
      }
    }
  }
  EXPECT_GT(scaled, 500) << scaled;
}

// Seasons (LeafSeason): in autumn the documented share of leaves turns, each part-way or fully
// (autumn^m, m in [kLeastTurn, 1]: pigments' absorbances add); the others keep their colour;
// spring tints every leaf alike; and a turned leaf never scatters more than it receives.
TEST(LeafSeason, AutumnTurnsTheDocumentedShareOfLeavesPartWayOrFully) {
  LeafSeason s;
  s.turned = 0.85f;
  s.autumn = {6.0f, 2.5f, 0.7f};
  const int n = 20000;
  int turned = 0;
  double mean_m = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 t = s.tint(derive_key(17, static_cast<std::uint64_t>(i)));
    if (t == glm::vec3(1.0f)) continue;
    ++turned;
    const double m = std::log(t.x) / std::log(6.0);  // from the red channel
    ASSERT_GE(m, LeafSeason::kLeastTurn - 1e-5);
    ASSERT_LE(m, 1.0 + 1e-5);
    EXPECT_NEAR(t.y, std::pow(2.5, m), 1e-4);
    EXPECT_NEAR(t.z, std::pow(0.7, m), 1e-4);
    mean_m += m;
  }
  // Binomial: σ of the share is 0.0025 at n = 20,000.
  EXPECT_NEAR(turned / double(n), 0.85, 0.01);
  EXPECT_NEAR(mean_m / turned, 0.5 * (1.0 + LeafSeason::kLeastTurn), 0.01);
  LeafSeason spring;
  spring.spring = {1.4f, 1.1f, 1.0f};
  EXPECT_EQ(spring.tint(1), spring.spring);
  EXPECT_EQ(spring.tint(2), spring.spring);
  EXPECT_FALSE(LeafSeason{}.any());
}

TEST(LeafSeason, ATurnedLeafNeverCreatesEnergy) {
  LeafMaterial m;
  m.front = {0.085f, 0.14f, 0.042f};
  m.back = {0.11f, 0.16f, 0.06f};
  m.transmittance = {0.06f, 0.10f, 0.012f};
  m.season.turned = 0.85f;
  m.season.autumn = glm::vec3(0.55f, 0.33f, 0.03f) / m.front;
  m.variation = {0.15f, 0.1f, 0.2f};
  int changed = 0;
  for (int i = 0; i < 3000; ++i) {
    for (const bool back : {false, true}) {
      SurfacePoint p;
      p.leaf_back = back;
      p.leaf_key = derive_key(5, static_cast<std::uint64_t>(i));
      const SurfaceBsdf b = m.bsdf(p);
      const LeafBsdf& l = std::get<LeafBsdf>(b.lobes);
      for (int c = 0; c < 3; ++c) ASSERT_LE(l.reflectance[c] + l.transmittance[c], 1.0 + 1e-12);
      if (!back && l.reflectance.x > 0.2) ++changed;
    }
  }
  EXPECT_GT(changed, 2000);  // most fronts turned golden: red up from 0.085
}

}  // namespace
}  // namespace arbor::materials
