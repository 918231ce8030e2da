// Tests of the leaf BSDF: sampling matches the pdf (chi-square over both hemispheres), energy,
// reciprocity.
#include "materials/leaf_bsdf.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "chi_square.h"
#include "common/rng.h"
#include "common/math.h"

namespace arbor::materials {

TEST(LeafBsdf, SamplingMatchesPdfChiSquare) {
  const LeafBsdf bsdf{Rgb(0.3, 0.5, 0.1), Rgb(0.6, 0.3, 0.2)};
  const Dir wo = glm::normalize(Dir(0.2, 0.1, 0.8));
  const int n_theta = 10, n_phi = 16, samples = 400000;
  // Cells over cos θ in [-1, 1] (both hemispheres) × φ.
  std::vector<double> observed(2 * n_theta * n_phi, 0.0);
  Rng rng(21);
  for (int i = 0; i < samples; ++i) {
    const BsdfSample s = bsdf.sample(wo, {rng.uniform(), rng.uniform(), rng.uniform()});
    ASSERT_GT(s.pdf, 0.0);
    ASSERT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-12);
    const int t = std::min(2 * n_theta - 1, static_cast<int>((s.wi.z + 1.0) * n_theta));
    double phi = std::atan2(s.wi.y, s.wi.x);
    if (phi < 0) phi += 2 * kPi;
    const int p = std::min(n_phi - 1, static_cast<int>(phi / (2 * kPi) * n_phi));
    observed[t * n_phi + p] += 1.0;
  }
  const double pr = bsdf.reflect_probability();
  double chi2 = 0.0;
  for (int t = 0; t < 2 * n_theta; ++t) {
    const double c0 = double(t) / n_theta - 1.0, c1 = double(t + 1) / n_theta - 1.0;
    // ∫ |cos θ| / π d(cos θ) dφ over the cell, times the lobe's probability.
    const double lobe = c0 >= 0.0 ? pr : 1.0 - pr;
    const double p_cell =
        lobe * std::fabs(c1 * std::fabs(c1) - c0 * std::fabs(c0)) / 2.0 / n_phi * 2.0;
    for (int p = 0; p < n_phi; ++p) {
      const double expected = p_cell * samples;
      const double d = observed[t * n_phi + p] - expected;
      chi2 += d * d / expected;
    }
  }
  // 319 degrees of freedom: the 99.9th percentile of χ² is about 405.
  EXPECT_LT(chi2, 405.0);
}

TEST(LeafBsdf, SamplingMatchesItsOwnPdfFromBothSides) {
  const LeafBsdf bsdf{Rgb(0.2, 0.3, 0.1), Rgb(0.5, 0.4, 0.2)};
  for (const Dir& wo : {glm::normalize(Dir(0.4, -0.2, 0.7)), glm::normalize(Dir(0.1, 0.3, -0.9))}) {
    const auto r = testing::chi_square(
        [&](Rng& rng) {
          return bsdf.sample(wo, {rng.uniform(), rng.uniform(), rng.uniform()});
        },
        [&](const Dir& wi) { return bsdf.pdf(wo, wi); }, 200000, 17);
    EXPECT_LT(r.chi2, testing::chi_square_critical(r.degrees_of_freedom));
  }
}

TEST(LeafBsdf, ReflectsAndTransmitsExactlyItsAlbedos) {
  // Estimate ∫ f |cos| dω per hemisphere by importance sampling: R on wo's side, T beyond.
  const LeafBsdf bsdf{Rgb(0.3, 0.5, 0.1), Rgb(0.6, 0.3, 0.2)};
  Rng rng(4);
  Rgb reflected(0.0), transmitted(0.0);
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const BsdfSample s = bsdf.sample(Dir(0, 0, 1), {rng.uniform(), rng.uniform(), rng.uniform()});
    const Rgb w = s.value * std::fabs(s.wi.z) / s.pdf;
    (s.wi.z > 0 ? reflected : transmitted) += w / double(n);
  }
  EXPECT_NEAR(reflected.x, 0.3, 0.01);
  EXPECT_NEAR(reflected.y, 0.5, 0.01);
  EXPECT_NEAR(transmitted.x, 0.6, 0.01);
  EXPECT_NEAR(transmitted.z, 0.2, 0.01);
  EXPECT_LE(reflected.x + transmitted.x, 1.0 + 0.02);
}

TEST(LeafBsdf, IsReciprocalOnBothSides) {
  const LeafBsdf bsdf{Rgb(0.3), Rgb(0.5)};
  const Dir a = glm::normalize(Dir(0.1, 0.2, 0.9)), b = glm::normalize(Dir(-0.5, 0.3, -0.4));
  EXPECT_EQ(bsdf.eval(a, b), bsdf.eval(b, a));
  EXPECT_EQ(bsdf.eval(a, b), Rgb(0.5 / kPi));
  EXPECT_EQ(bsdf.eval(a, Dir(b.x, b.y, -b.z)), Rgb(0.3 / kPi));
}

}  // namespace arbor::materials
