// The ground's detail (materials/ground.h, issue 29): finer scales that keep the mean, stones
// covering what their density says and only on soil, litter covering its fraction, and the sky's
// ground albedo (spec::mean_albedo) agreeing with the ground it stands for.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "spec/scene_desc.h"
#include "materials/ground.h"

namespace arbor::materials {

namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

struct Sample {
  double mean = 0.0, spread = 0.0;  // of the luminance
};

// The luminance over a 40 m square, `n` × `n` points `step` metres apart from (x0, y0).
Sample sample(const GroundMaterial& g, int n, double step, double x0 = 0.31, double y0 = 0.77) {
  double s = 0.0, s2 = 0.0;
  SurfacePoint p;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      p.ground = glm::vec2(static_cast<float>(x0 + i * step), static_cast<float>(y0 + j * step));
      const double y = luminance(g.albedo_at(p));
      s += y;
      s2 += y * y;
    }
  }
  const double m = s / (n * n);
  return {m, std::sqrt(std::max(0.0, s2 / (n * n) - m * m))};
}

}  // namespace

// Detail varies the bare soil's brightness at every scale it has — 2 cm apart as well as 1 m —
// and keeps its mean within 2 %.
TEST(GroundDetail, FinerScalesVaryTheSoilAndKeepItsMean) {
  GroundMaterial g;
  g.albedo = glm::vec3(0.16f, 0.14f, 0.10f);
  g.scale = 2.5f;
  g.detail = 0.6f;
  const double plain = luminance(g.albedo);
  const Sample coarse = sample(g, 200, 0.2), fine = sample(g, 200, 0.004);
  std::printf("  mean %.4f (plain %.4f); spread over 40 m %.4f, over 0.8 m %.4f\n", coarse.mean,
              plain, coarse.spread, fine.spread);
  EXPECT_NEAR(coarse.mean, plain, 0.02 * plain);
  EXPECT_GT(coarse.spread, 0.05 * plain);
  EXPECT_GT(fine.spread, 0.02 * plain);
  g.detail = 0.0f;
  EXPECT_EQ(sample(g, 20, 0.2).spread, 0.0);
}

// Stones of density D cover D × 8.2 cm² of the soil (π × 4 × 3 cm / 4 × 0.825 × 1.053, as the
// bark's marks), within 5 %, and none of the grass.
TEST(GroundDetail, StonesCoverWhatTheirDensitySaysAndOnlyTheSoil) {
  GroundMaterial g;
  g.albedo = glm::vec3(0.0f);
  g.stone_albedo = glm::vec3(1.0f);
  g.scale = 2.5f;
  g.stones = 20.0f;
  const double covered = sample(g, 1000, 0.01).mean;  // a 10 m square
  std::printf("  stones cover %.5f (expected %.5f)\n", covered, 20.0 * 8.2e-4);
  EXPECT_NEAR(covered, 20.0 * 8.2e-4, 0.05 * 20.0 * 8.2e-4);
  g.patch_albedo = glm::vec3(0.0f);
  g.set_cover(1.0f);
  EXPECT_EQ(sample(g, 300, 0.01).mean, 0.0);
}

// Litter covers its fraction of the ground (its patches' noise at its quantile, soft-edged),
// within 5 % of the ground.
TEST(GroundDetail, LitterCoversItsFraction) {
  for (float cover : {0.1f, 0.4f}) {
    GroundMaterial g;
    g.albedo = glm::vec3(0.0f);
    g.litter_albedo = glm::vec3(1.0f);
    g.scale = 3.0f;
    g.set_litter(cover);
    const double covered = sample(g, 400, 0.25).mean;  // 100 m
    std::printf("  litter %.2f covers %.4f\n", cover, covered);
    EXPECT_NEAR(covered, cover, 0.05);
  }
}

// spec::mean_albedo, the sky's ground albedo, is the ground's sampled mean luminance within 3 %
// with patches, detail, stones and litter all on.
TEST(GroundDetail, TheSkysGroundAlbedoIsTheGroundsMean) {
  spec::GroundDesc d;
  d.patch_cover = 0.6;
  d.patch_scale = 2.5;
  d.detail = 0.6;
  d.stones = 8.0;
  d.litter = 0.15;
  GroundMaterial g;
  g.albedo = glm::vec3(d.albedo[0], d.albedo[1], d.albedo[2]);
  g.patch_albedo = glm::vec3(d.patch_albedo[0], d.patch_albedo[1], d.patch_albedo[2]);
  g.scale = 2.5f;
  g.set_cover(0.6f);
  g.detail = 0.6f;
  g.stones = 8.0f;
  g.set_litter(0.15f);
  const double sampled = sample(g, 500, 0.2).mean;  // 100 m
  std::printf("  mean albedo %.4f, sampled %.4f\n", spec::mean_albedo(d), sampled);
  EXPECT_NEAR(spec::mean_albedo(d), sampled, 0.03 * sampled);
}

}  // namespace arbor::materials
