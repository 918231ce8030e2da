// The procedural leaf texture (materials/leaf_texture.h): where its midrib, veins and margin are,
// how much of the leaf they cover, and that the blade between them keeps the leaf's colour.
#include "materials/leaf_texture.h"

#include <cmath>

#include <gtest/gtest.h>

#include "materials/leaf.h"

namespace arbor::materials {
namespace {

TEST(LeafTexture, MidribVeinsAndMarginArePaleAndTheBladeIsUntouched) {
  const LeafTexture t{1.0f, 8};
  // The midrib all along the leaf.
  for (float v : {0.05f, 0.5f, 0.95f}) EXPECT_FLOAT_EQ(t.mask({0.5f, v}), 1.0f) << v;
  // A secondary vein: v − 1.2 |u − ½| = 3/8 at u = 0.6 is v = 0.495.
  EXPECT_NEAR(t.mask({0.6f, 0.495f}), 0.7f, 1e-5f);
  EXPECT_NEAR(t.mask({0.4f, 0.495f}), 0.7f, 1e-5f);  // its pair on the other side
  // Between two veins the blade keeps its colour.
  EXPECT_FLOAT_EQ(t.mask({0.6f, 0.495f + 0.0625f}), 0.0f);
  EXPECT_EQ(t.tint({0.6f, 0.495f + 0.0625f}), glm::vec3(1.0f));
  // The margin.
  EXPECT_FLOAT_EQ(t.mask({0.0f, 0.5f}), 0.5f);
  EXPECT_FLOAT_EQ(t.mask({1.0f, 0.5f}), 0.5f);
  // Paler and yellower: red gains most, blue least.
  const glm::vec3 rib = t.tint({0.5f, 0.5f});
  EXPECT_GT(rib.r, rib.g);
  EXPECT_GT(rib.g, rib.b);
  EXPECT_GT(rib.b, 1.0f);
  EXPECT_FALSE(LeafTexture{}.any());
}

// How much of the leaf's card the pattern pales (mask > 0.1), over a 400 × 400 grid: the midrib
// and 8 vein pairs 12 % (measured), the margins 18 % (their eighth of the card's width on each
// side, less the soft inner edge). Power: veins twice as wide, or margins a quarter of the width
// on each side, leave the bands.
TEST(LeafTexture, ThePatternCoversTheDocumentedShareOfTheLeaf) {
  const LeafTexture t{1.0f, 8};
  int veins = 0, margin = 0, n = 0;
  for (int i = 0; i < 400; ++i) {
    for (int j = 0; j < 400; ++j) {
      const glm::vec2 uv((i + 0.5f) / 400.0f, (j + 0.5f) / 400.0f);
      const float m = t.mask(uv);
      ++n;
      if (std::fabs(uv.x - 0.5f) >= 0.375f) {
        margin += m > 0.1f ? 1 : 0;
      } else {
        veins += m > 0.1f ? 1 : 0;
      }
    }
  }
  const double vein_share = double(veins) / n, margin_share = double(margin) / n;
  EXPECT_GT(vein_share, 0.11);
  EXPECT_LT(vein_share, 0.135);
  EXPECT_GT(margin_share, 0.165);
  EXPECT_LT(margin_share, 0.20);
}

// The texture is part of the tint: the BSDF and the albedo AOV show it, and R + T stays ≤ 1.
TEST(LeafTexture, TheLeafMaterialShowsItAndCreatesNoEnergy) {
  LeafMaterial m;
  m.front = {0.10f, 0.45f, 0.05f};
  m.back = m.front;
  m.transmittance = {0.10f, 0.45f, 0.05f};
  m.texture = {2.0f, 8};
  SurfacePoint rib, blade;
  rib.uv = {0.5f, 0.5f};
  blade.uv = {0.6f, 0.495f + 0.0625f};
  EXPECT_EQ(m.albedo_at(blade), m.front);
  EXPECT_GT(m.albedo_at(rib).r, m.front.r);
  const LeafBsdf& l = std::get<LeafBsdf>(m.bsdf(rib).lobes);
  for (int c = 0; c < 3; ++c) EXPECT_LE(l.reflectance[c] + l.transmittance[c], 1.0 + 1e-12);
}

}  // namespace
}  // namespace arbor::materials
