// Tests of the Oren–Nayar BSDF and image height maps.
#include "materials/oren_nayar.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>

#include "common/error.h"
#include "common/rng.h"
#include "chi_square.h"
#include "materials/textures.h"

namespace arbor::materials {

TEST(OrenNayar, SamplingMatchesPdfChiSquare) {
  for (double sigma : {0.0, 0.3, 0.8}) {
    for (double theta_o : {0.1, 0.9, 1.4}) {
      const OrenNayar on{Rgb(0.6), sigma};
      const Dir wo(std::sin(theta_o), 0.0, std::cos(theta_o));
      const auto r = testing::chi_square(
          [&](Rng& rng) {
            return on.sample(wo, {0.0, rng.uniform(), rng.uniform()});
          },
          [&](const Dir& wi) { return on.pdf(wo, wi); }, 200000, 31);
      EXPECT_LT(r.chi2, testing::chi_square_critical(r.degrees_of_freedom))
          << "sigma " << sigma << " theta_o " << theta_o;
    }
  }
}

TEST(OrenNayar, EvalIsTheQualitativeModelOfThePaper) {
  // Oren & Nayar 1994, eq. 30 in angles: f = ρ/π (A + B max(0, cos(φi − φo)) sin α tan β),
  // A = 1 − 0.5 σ²/(σ² + 0.33), B = 0.45 σ²/(σ² + 0.09), α = max(θi, θo), β = min(θi, θo).
  const double rho = 0.6;
  for (double sigma : {0.2, 0.5, 1.0}) {
    const OrenNayar on{Rgb(rho), sigma};
    const double s2 = sigma * sigma, A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
    for (double ti : {0.2, 0.8, 1.3}) {
      for (double to : {0.1, 0.6, 1.2}) {
        for (double dphi : {0.0, 1.0, 2.5}) {
          const Dir wi(std::sin(ti), 0.0, std::cos(ti));
          const Dir wo(std::sin(to) * std::cos(dphi), std::sin(to) * std::sin(dphi), std::cos(to));
          const double expected = rho / kPi *
                                  (A + B * std::max(0.0, std::cos(dphi)) *
                                           std::sin(std::max(ti, to)) * std::tan(std::min(ti, to)));
          EXPECT_NEAR(on.eval(wo, wi).x, expected, 1e-12)
              << "sigma " << sigma << " theta_i " << ti << " theta_o " << to << " dphi " << dphi;
        }
      }
    }
    // Seen from the normal (θo = 0, so tan β = 0) the directional albedo is exactly ρ A.
    const double albedo = testing::hemisphere_integral(
        [&](const Dir& wi) { return on.eval(Dir(0.0, 0.0, 1.0), wi).x * wi.z; });
    EXPECT_NEAR(albedo, rho * A, 1e-5) << "sigma " << sigma;
  }
}

TEST(OrenNayar, ZeroRoughnessIsLambert) {
  // At σ = 0 the model is Lambert's: f = ρ / π for any pair of directions above the surface.
  const OrenNayar on{Rgb(0.4), 0.0};
  const Dir a = glm::normalize(Dir(0.3, 0.1, 0.8)), b = glm::normalize(Dir(-0.4, 0.2, 0.5));
  EXPECT_NEAR(on.eval(a, b).x, 0.4 / kPi, 1e-12);
  EXPECT_NEAR(on.eval(b, a).x, 0.4 / kPi, 1e-12);
}

TEST(OrenNayar, IsReciprocalAndConservesEnergy) {
  const OrenNayar on{Rgb(1.0), 0.5};  // about 29° of slope deviation, albedo 1
  Rng rng(8);
  for (int k = 0; k < 200; ++k) {
    Dir a(rng.symmetric(), rng.symmetric(), std::fabs(rng.symmetric()) + 0.05);
    Dir b(rng.symmetric(), rng.symmetric(), std::fabs(rng.symmetric()) + 0.05);
    a = glm::normalize(a);
    b = glm::normalize(b);
    EXPECT_NEAR(on.eval(a, b).x, on.eval(b, a).x, 1e-12);
  }
  // Directional albedo ∫ f cos dωi ≤ 1 for every outgoing direction (qualitative model: it is).
  for (double theta_o : {0.0, 0.5, 1.0, 1.4}) {
    const Dir wo(std::sin(theta_o), 0.0, std::cos(theta_o));
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const BsdfSample s = on.sample(wo, {0.0, rng.uniform(), rng.uniform()});
      sum += s.value.x * std::fabs(s.wi.z) / s.pdf;
    }
    EXPECT_LE(sum / n, 1.0 + 0.01) << "theta_o " << theta_o;
    EXPECT_GT(sum / n, 0.7);
  }
}

TEST(HeightMap, WrapsAndInterpolates) {
  const HeightMap m({0.0f, 1.0f, 2.0f, 3.0f}, 2, 2);  // rows: 0 1 / 2 3
  EXPECT_FLOAT_EQ(m.sample(0.25, 0.25), 0.0f);        // pixel centres
  EXPECT_FLOAT_EQ(m.sample(0.75, 0.25), 1.0f);
  EXPECT_FLOAT_EQ(m.sample(0.75, 0.75), 3.0f);
  EXPECT_FLOAT_EQ(m.sample(1.25, -0.75), 0.0f);  // wraps in both directions
  EXPECT_FLOAT_EQ(m.sample(0.5, 0.25), 0.5f);    // halfway between 0 and 1
  EXPECT_FLOAT_EQ(m.sample(0.0, 0.25), 0.5f);    // across the seam: between 1 and 0
}

TEST(ColorMap, DecodesSrgbImagesAndRejectsAlbedosAboveOne) {
  const std::string config = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";
  const std::string png = ::testing::TempDir() + "grey.png";
  OIIO::ImageBuf grey(OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::UINT8));
  const float half[3] = {128.0f / 255.0f, 128.0f / 255.0f, 1.0f};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) grey.setpixel(x, y, half);
  ASSERT_TRUE(grey.write(png));
  const ColorMap decoded(png, config);
  // sRGB 128/255 is 0.2159 linear; 1 stays 1.
  EXPECT_NEAR(decoded.sample(0.3, 0.7).x, 0.2159f, 2e-3f);
  EXPECT_NEAR(decoded.sample(0.3, 0.7).z, 1.0f, 1e-4f);

  const std::string exr = ::testing::TempDir() + "bright.exr";
  OIIO::ImageBuf bright(OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::FLOAT));
  const float ok[3] = {0.25f, 0.5f, 0.75f}, too_much[3] = {1.5f, 0.5f, 0.5f};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) bright.setpixel(x, y, ok);
  ASSERT_TRUE(bright.write(exr));
  EXPECT_NEAR(ColorMap(exr, config).sample(0.1, 0.1).y, 0.5f, 1e-6f);  // linear files stay linear
  bright.setpixel(1, 1, too_much);
  ASSERT_TRUE(bright.write(exr));
  try {
    ColorMap rejected(exr, config);
    FAIL() << "an albedo above 1 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("[0, 1]"), std::string::npos);
    EXPECT_EQ(e.where().path, exr);
  }
}

}  // namespace arbor::materials
