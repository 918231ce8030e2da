// The material layer: bark bump mapping tilts the normal by the height gradient (worked out for
// a ramp image), bark images tile whole times round a limb, leaves take their side's reflectance
// and their tint, and one dispatch gives both the BSDF and the albedo AOV.
#include "materials/material.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/math.h"

namespace arbor::materials {

namespace {

// A point on a limb of radius 0.1 m: normal +x, the limb along +z.
SurfacePoint limb_point(float along, float azimuth) {
  SurfacePoint p;
  p.shading_normal = p.geometric_normal = glm::vec3(1, 0, 0);
  p.tangent = glm::vec3(0, 0, 1);
  p.along = along;
  p.azimuth = azimuth;
  p.radius = 0.1f;
  return p;
}

}  // namespace

TEST(BarkMaterial, ABumpRampTiltsTheNormalByItsSlope) {
  // Height rising linearly along the limb, 0 → 1 over the image (rows are v): with a tile of
  // 0.25 m the slope is 4 per metre, so a relief of h metres tilts the normal by atan(4 h)
  // against the slope (towards −tangent). Away from the ramp's wrap-around row.
  std::vector<float> ramp;
  const int n = 64;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < 4; ++x) ramp.push_back((y + 0.5f) / n);
  }
  const HeightMap map(ramp, 4, n);
  BarkMaterial bark;
  bark.bump_map = &map;
  bark.bump_tile = 0.25f;
  bark.bump_height = 0.01f;
  const glm::vec3 bumped = bark.bumped_normal(limb_point(0.1f, 1.0f));
  const double tilt = std::atan2(-bumped.z, bumped.x);
  EXPECT_NEAR(tilt, std::atan(4.0 * 0.01), 1e-3);
  EXPECT_NEAR(bumped.y, 0.0f, 1e-4f);
  EXPECT_NEAR(glm::length(bumped), 1.0f, 1e-6f);
  // No relief, or no limb radius: the normal is left alone.
  bark.bump_height = 0.0f;
  EXPECT_EQ(bark.bumped_normal(limb_point(0.1f, 1.0f)), glm::vec3(1, 0, 0));
}

TEST(BarkMaterial, ABumpRampRoundTheLimbTiltsTheNormalSideways) {
  // Height rising with azimuth, one ramp per repeat: a limb of radius 0.1 m has round(2π 0.1 /
  // 0.25) = 3 repeats round it, so the slope is 3 / (2π 0.1) per metre of arc, and the normal
  // tilts against it, towards −(tangent × normal) = −y.
  std::vector<float> ramp;
  const int n = 64;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < n; ++x) ramp.push_back((x + 0.5f) / n);
  }
  const HeightMap map(ramp, n, 4);
  BarkMaterial bark;
  bark.bump_map = &map;
  bark.bump_height = 0.01f;
  const glm::vec3 bumped = bark.bumped_normal(limb_point(0.1f, 1.0f));
  const double slope = 3.0 / (2.0 * kPi * 0.1);
  EXPECT_NEAR(std::atan2(-bumped.y, bumped.x), std::atan(slope * 0.01), 1e-3);
  EXPECT_NEAR(bumped.z, 0.0f, 1e-4f);
}

TEST(BarkMaterial, ThePrimitivesColourMultipliesTheAlbedo) {
  BarkMaterial bark;
  bark.albedo = glm::vec3(0.5f);
  SurfacePoint p = limb_point(0.0f, 0.0f);
  p.color = glm::vec3(0.8f, 1.0f, 1.0f);
  EXPECT_NEAR(bark.albedo_at(p).x, 0.4f, 1e-6f);
  EXPECT_NEAR(bark.albedo_at(p).y, 0.5f, 1e-6f);
}

TEST(LeafMaterial, TheSideHitAndTheTintChooseTheReflectance) {
  LeafMaterial leaf;
  leaf.front = glm::vec3(0.1f, 0.2f, 0.3f);
  leaf.back = glm::vec3(0.3f, 0.2f, 0.1f);
  leaf.transmittance = glm::vec3(0.4f);
  SurfacePoint p;
  p.color = glm::vec3(0.5f, 1.0f, 1.0f);
  EXPECT_NEAR(leaf.albedo_at(p).x, 0.05f, 1e-7f);
  p.leaf_back = true;
  EXPECT_NEAR(leaf.albedo_at(p).x, 0.15f, 1e-7f);
  leaf.tinted = false;  // mesh leaves: as given
  EXPECT_NEAR(leaf.albedo_at(p).x, 0.3f, 1e-7f);
}

TEST(Material, TheBsdfAndTheAlbedoAovCarryEachMaterialsAlbedo) {
  BarkMaterial b;
  b.albedo = glm::vec3(0.3f, 0.25f, 0.2f);
  b.bump_height = 0.004f;  // procedural furrows
  b.roughness = 0.3f;
  const Material bark = b;
  LeafMaterial l;
  l.front = glm::vec3(0.1f);
  l.back = glm::vec3(0.2f);
  l.transmittance = glm::vec3(0.5f);
  const Material leaf = l;
  const Material ground = DiffuseMaterial{glm::vec3(0.16f, 0.14f, 0.1f)};
  for (float a : {0.0f, 0.3f, 1.7f}) {
    SurfacePoint p = limb_point(a, 2.0f * a);
    p.leaf_back = a > 1.0f;
    // Each material's albedo as its own parameters say (no pattern, no variation, no map here).
    const glm::vec3 own[] = {b.albedo, p.leaf_back ? l.back : l.front,
                             glm::vec3(0.16f, 0.14f, 0.1f)};
    int k = 0;
    for (const Material* m : {&bark, &leaf, &ground}) {
      const SurfaceBsdf b = m->bsdf(p);
      EXPECT_EQ(b.albedo, own[k]) << k;
      EXPECT_EQ(m->albedo_at(p), own[k++]);
      EXPECT_EQ(b.transmits(), m == &leaf);
      EXPECT_EQ(b.flags() & kReflection, kReflection);
      EXPECT_GE(glm::dot(b.normal, p.geometric_normal), 0.0f);  // kept on the geometry's side
      EXPECT_NEAR(glm::length(b.normal), 1.0f, 1e-5f);
    }
    EXPECT_EQ(std::get<OrenNayar>(bark.bsdf(p).lobes).sigma, 0.3f);
    EXPECT_EQ(std::get<LeafBsdf>(leaf.bsdf(p).lobes).transmittance, glm::dvec3(glm::vec3(0.5f)));
  }
}

}  // namespace arbor::materials

namespace arbor::materials {

TEST(GroundMaterial, PatchesCoverTheAskedFractionWithSoftEdges) {
  GroundMaterial g;
  g.scale = 3.0f;
  for (float cover : {0.2f, 0.5f, 0.8f}) {
    g.set_cover(cover);
    int inside = 0, soft = 0, n = 0;
    for (int i = 0; i < 400; ++i) {
      for (int j = 0; j < 400; ++j) {
        const float w = g.patch({i * 0.5f - 100.0f, j * 0.5f - 100.0f});  // 200 m × 200 m
        ASSERT_GE(w, 0.0f);
        ASSERT_LE(w, 1.0f);
        inside += w > 0.5f ? 1 : 0;
        soft += (w > 0.0f && w < 1.0f) ? 1 : 0;
        ++n;
      }
    }
    EXPECT_NEAR(double(inside) / n, cover, 0.05) << "cover " << cover;
    EXPECT_GT(soft, n / 50);  // the edges blend
    EXPECT_LT(soft, n / 2);   // but most of the ground is one or the other
  }
  g.set_cover(0.0f);
  EXPECT_EQ(g.patch({1.0f, 2.0f}), 0.0f);
}

// The threshold is the (1 − cover) quantile and the edge a quarter of the 16–84 % spread of the
// noise's fixed 512 × 512 sample: exactly the values of the sorted sample at those indices.
TEST(GroundMaterial, ThresholdAndEdgeAreTheSortedSamplesQuantiles) {
  std::vector<double> v;
  for (int i = 0; i < 512; ++i) {
    for (int j = 0; j < 512; ++j) v.push_back(GroundMaterial::noise(i * 0.137, j * 0.137));
  }
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[static_cast<std::size_t>(q * v.size())]; };
  for (float cover : {0.1f, 0.5f, 0.93f}) {
    GroundMaterial g;
    g.set_cover(cover);
    EXPECT_EQ(g.threshold, at(1.0 - cover)) << cover;
    EXPECT_EQ(g.edge, 0.25 * (at(0.84) - at(0.16))) << cover;
  }
}

TEST(GroundMaterial, TheAlbedoMixesTheTwoColoursByThePatch) {
  GroundMaterial g;
  g.albedo = glm::vec3(0.16f, 0.14f, 0.10f);
  g.patch_albedo = glm::vec3(0.06f, 0.11f, 0.035f);
  g.set_cover(0.5f);
  const Material ground = g;
  SurfacePoint p;
  bool saw_soil = false, saw_grass = false;
  for (int i = 0; i < 2000 && !(saw_soil && saw_grass); ++i) {
    p.ground = glm::vec2(i * 0.37f, i * 0.11f);
    const float w = g.patch(p.ground);
    const glm::vec3 a = ground.albedo_at(p);
    EXPECT_NEAR(a.x, 0.16f + (0.06f - 0.16f) * w, 1e-6f);
    EXPECT_EQ(glm::vec3(std::get<OrenNayar>(ground.bsdf(p).lobes).albedo), a);
    saw_soil = saw_soil || w == 0.0f;
    saw_grass = saw_grass || w == 1.0f;
  }
  EXPECT_TRUE(saw_soil);
  EXPECT_TRUE(saw_grass);
}

}  // namespace arbor::materials
