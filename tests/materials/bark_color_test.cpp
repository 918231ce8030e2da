// Bark colour by its relief and marks (materials/bark_color.h): the furrows' albedo where the bark
// is low and the ridges' where it is high, lenticels covering what their density and size say,
// lying across the limb, and the trunk's base darker.
#include "materials/bark_color.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "materials/bark.h"
#include "materials/bark_noise.h"

namespace arbor::materials {

namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Bark points on a trunk of radius 0.2 m, 2 m long, on a regular grid of `n` × `n`.
template <class F>
void over_a_trunk(int n, F f) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) f(2.0 * (i + 0.5) / n, 6.283185307 * (j + 0.5) / n, 0.2);
}

}  // namespace

// The albedo's luminance and the bark height correlate (ρ > 0.9 with furrows 0.1 against ridges
// 0.5); deep in the furrows the albedo is the furrows', high on the ridges the bark's own.
TEST(BarkColour, TheAlbedoFollowsTheRelief) {
  BarkPattern p;
  p.furrows = true;
  p.furrow_albedo = glm::vec3(0.1f);
  const glm::vec3 ridge(0.5f);
  std::vector<double> h, a;
  double low = 0.0, high = 0.0;
  int n_low = 0, n_high = 0;
  over_a_trunk(200, [&](double along, double azimuth, double radius) {
    const double height = bark_height(along, azimuth, radius);
    const float y = luminance(p.albedo(ridge, height, along, azimuth, radius, 5.0f));
    h.push_back(height);
    a.push_back(y);
    if (height < 0.6) low += y, ++n_low;
    if (height > 0.88) high += y, ++n_high;
  });
  double mh = 0, ma = 0;
  for (std::size_t i = 0; i < h.size(); ++i) mh += h[i] / h.size(), ma += a[i] / a.size();
  double shh = 0, saa = 0, sha = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    shh += (h[i] - mh) * (h[i] - mh);
    saa += (a[i] - ma) * (a[i] - ma);
    sha += (h[i] - mh) * (a[i] - ma);
  }
  const double rho = sha / std::sqrt(shh * saa);
  std::printf("  correlation %.3f, furrows %.3f (%d), ridges %.3f (%d)\n", rho, low / n_low, n_low,
              high / n_high, n_high);
  EXPECT_GT(rho, 0.9);
  ASSERT_GT(n_low, 100);
  ASSERT_GT(n_high, 100);
  EXPECT_NEAR(low / n_low, 0.1, 0.01);
  EXPECT_NEAR(high / n_high, 0.5, 0.02);
}

// Lenticels of density D, w × h metres: the share of bark they cover is D × π w h / 4 × 0.825
// (the soft edge: the unit disk's integral of min(1, (1 − ρ²)/0.35)) × 1.053 (E[s²] of sizes
// s uniform in 0.6–1.4), within 5 %; and they lie across the limb: a covered point's neighbour
// 3 mm round the limb is covered more often than its neighbour 3 mm along it.
TEST(BarkColour, LenticelsCoverWhatTheirDensityAndSizeSayAcrossTheLimb) {
  const float density = 400.0f, w = 0.009f, h = 0.0018f;
  double covered = 0.0, round = 0.0, along_too = 0.0;
  int n = 0;
  const double r = 0.2;
  for (int i = 0; i < 2000; ++i) {
    for (int j = 0; j < 1000; ++j) {
      const double along = 4.0 * (i + 0.5) / 2000, azimuth = 6.283185307 * (j + 0.5) / 1000;
      const float c = mark_coverage(along, azimuth, r, density, w, h, 7u);
      covered += c;
      ++n;
      if (c > 0.9f) {
        round += mark_coverage(along, azimuth + 0.003 / r, r, density, w, h, 7u) > 0.5f;
        along_too += mark_coverage(along + 0.003, azimuth, r, density, w, h, 7u) > 0.5f;
      }
    }
  }
  const double expected = density * 3.14159265 * w * h / 4.0 * 0.825 * (1.0 + 0.64 / 12.0);
  std::printf("  covered %.5f (expected %.5f); neighbours round %g, along %g\n", covered / n,
              expected, round, along_too);
  EXPECT_NEAR(covered / n, expected, 0.05 * expected);
  EXPECT_GT(round, 3.0 * along_too);
}

// Below base_height the trunk's albedo is darker, most at the ground; above it, the pattern is
// the base's absence bit for bit.
TEST(BarkColour, TheTrunksBaseIsDarker) {
  BarkPattern p;
  p.furrow_albedo = glm::vec3(0.25f);
  p.base_height = 1.5f;
  const glm::vec3 ridge(0.6f);
  double at[3] = {0, 0, 0};
  const float z[3] = {0.0f, 0.75f, 2.0f};
  BarkPattern none = p;
  none.base_height = 0.0f;
  over_a_trunk(60, [&](double along, double azimuth, double radius) {
    const double height = bark_height(along, azimuth, radius);
    for (int k = 0; k < 3; ++k)
      at[k] += luminance(p.albedo(ridge, height, along, azimuth, radius, z[k])) / 3600.0;
    EXPECT_EQ(p.albedo(ridge, height, along, azimuth, radius, 2.0f),
              none.albedo(ridge, height, along, azimuth, radius, 2.0f));
  });
  std::printf("  mean luminance at 0, 0.75, 2 m: %.3f %.3f %.3f\n", at[0], at[1], at[2]);
  EXPECT_LT(at[0], 0.8 * at[2]);
  EXPECT_LT(at[0], at[1]);
  EXPECT_LT(at[1], at[2]);
}

// An albedo image wins over the pattern; without one, BarkMaterial's albedo is the pattern's.
TEST(BarkColour, TheMaterialUsesThePatternUnlessAnImageIsGiven) {
  BarkMaterial bark;
  bark.albedo = glm::vec3(0.5f);
  bark.pattern.furrows = true;
  bark.pattern.furrow_albedo = glm::vec3(0.1f);
  SurfacePoint p;
  p.azimuth = 1.1f;
  p.radius = 0.2f;
  p.height = 3.0f;
  // A point in a furrow, where the pattern shows.
  while (bark_height(p.along, p.azimuth, p.radius) > 0.7) p.along += 0.001f;
  const glm::vec3 expected = bark.pattern.albedo(
      bark.albedo, bark_height(p.along, p.azimuth, p.radius), p.along, p.azimuth, p.radius, 3.0f);
  EXPECT_EQ(bark.albedo_at(p), expected);
  EXPECT_NE(expected, bark.albedo);
}

}  // namespace arbor::materials
