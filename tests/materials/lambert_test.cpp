// Tests of the Lambertian BSDF: sampling matches its pdf (chi-square), energy, reciprocity.
#include "materials/lambert.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/rng.h"
#include "chi_square.h"
#include "common/math.h"

namespace arbor::mat {

TEST(Lambert, SamplingMatchesPdfChiSquare) {
  // Histogram of sampled directions over (cos θ, φ) cells against the pdf integrated per cell.
  const Lambert bsdf{Rgb(0.8)};
  const Dir wo = glm::normalize(Dir(0.3, -0.2, 0.9));
  const int n_theta = 10, n_phi = 20, samples = 200000;
  std::vector<double> observed(n_theta * n_phi, 0.0);
  Rng rng(11);
  for (int i = 0; i < samples; ++i) {
    const BsdfSample s = bsdf.sample(wo, {rng.uniform(), rng.uniform()});
    ASSERT_GT(s.pdf, 0.0);
    const int t = std::min(n_theta - 1, static_cast<int>(s.wi.z * n_theta));
    double phi = std::atan2(s.wi.y, s.wi.x);
    if (phi < 0) phi += 2 * kPi;
    const int p = std::min(n_phi - 1, static_cast<int>(phi / (2 * kPi) * n_phi));
    observed[t * n_phi + p] += 1.0;
  }
  // pdf = cos θ / π; over a cell [c0, c1] × [φ0, φ1] in cos θ: ∫ c/π dc dφ = (c1²-c0²)/2 · Δφ/π.
  double chi2 = 0.0;
  for (int t = 0; t < n_theta; ++t) {
    const double c0 = double(t) / n_theta, c1 = double(t + 1) / n_theta;
    const double p_cell = (c1 * c1 - c0 * c0) / 2.0 * (2 * kPi / n_phi) / kPi;
    for (int p = 0; p < n_phi; ++p) {
      const double expected = p_cell * samples;
      const double d = observed[t * n_phi + p] - expected;
      chi2 += d * d / expected;
    }
  }
  // 199 degrees of freedom: the 99.9th percentile of χ² is about 267.
  EXPECT_LT(chi2, 267.0);
}

TEST(Lambert, ReflectsExactlyItsAlbedo) {
  // By quadrature, independent of sampling: ∫ f cos θi dωi is the albedo from every outgoing
  // direction, and the pdf integrates to one.
  const Lambert bsdf{Rgb(0.3, 0.6, 1.0)};
  for (double theta_o : {0.0, 0.7, 1.45}) {
    const Dir wo(std::sin(theta_o), 0.0, std::cos(theta_o));
    for (int c = 0; c < 3; ++c) {
      const double reflected =
          testing::hemisphere_integral([&](const Dir& wi) { return bsdf.eval(wo, wi)[c] * wi.z; });
      EXPECT_NEAR(reflected, bsdf.albedo[c], 1e-5) << "theta_o " << theta_o << " channel " << c;
    }
    EXPECT_NEAR(testing::hemisphere_integral([&](const Dir& wi) { return bsdf.pdf(wo, wi); }), 1.0,
                1e-5);
  }
  // And each sample's weight value · cos / pdf is that albedo (the white furnace in one bounce).
  Rng rng(5);
  for (int i = 0; i < 1000; ++i) {
    const BsdfSample s =
        bsdf.sample(glm::normalize(Dir(0.2, 0.1, 0.9)), {rng.uniform(), rng.uniform()});
    const Rgb weight = s.value * std::fabs(s.wi.z) / s.pdf;
    EXPECT_NEAR(weight.x, 0.3, 1e-12);
    EXPECT_NEAR(weight.y, 0.6, 1e-12);
    EXPECT_NEAR(weight.z, 1.0, 1e-12);
  }
}

TEST(Lambert, IsReciprocalAndOneSided) {
  const Lambert bsdf{Rgb(0.5)};
  const Dir a = glm::normalize(Dir(0.1, 0.2, 0.9)), b = glm::normalize(Dir(-0.5, 0.3, 0.4));
  EXPECT_EQ(bsdf.eval(a, b), bsdf.eval(b, a));
  EXPECT_EQ(bsdf.eval(a, Dir(b.x, b.y, -b.z)), Rgb(0.0));
  EXPECT_EQ(bsdf.pdf(a, Dir(b.x, b.y, -b.z)), 0.0);
}

}  // namespace arbor::mat
