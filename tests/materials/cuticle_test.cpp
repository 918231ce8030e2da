// Tests of the leaf's cuticle coat and the coated leaf BSDF: Fresnel, the coat's albedo table
// against an independent integral, sampling against the pdf (χ²) at several roughnesses,
// reciprocity, energy (a white leaf scatters exactly what arrives; nothing ever scatters more).
#include "materials/cuticle.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "chi_square.h"
#include "common/math.h"
#include "common/rng.h"
#include "materials/leaf.h"
#include "materials/leaf_bsdf.h"

namespace arbor::materials {

namespace {
Dir at_angle(double mu, double phi = 0.0) {
  const double s = std::sqrt(1.0 - mu * mu);
  return Dir(s * std::cos(phi), s * std::sin(phi), mu);
}

// ∫ f(wo, wi) |cos θi| dωi over one hemisphere (z > 0 when upper), independently of sampling.
Rgb scattered(const LeafBsdf& b, const Dir& wo, bool upper, int n = 300) {
  Rgb sum(0.0);
  for (int c = 0; c < 3; ++c) {
    sum[c] = testing::hemisphere_integral(
        [&](const Dir& w) {
          const Dir wi(w.x, w.y, upper ? w.z : -w.z);
          return b.eval(wo, wi)[c] * w.z;
        },
        n);
  }
  return sum;
}
}  // namespace

TEST(CuticleCoat, FresnelIsTheDielectricsAtNormalGrazingAndBrewsterIncidence) {
  const double r0 = (1.45 - 1.0) / (1.45 + 1.0);
  EXPECT_NEAR(CuticleCoat::fresnel(1.0, 1.45), r0 * r0, 1e-12);  // 0.0337
  EXPECT_NEAR(CuticleCoat::fresnel(0.0, 1.45), 1.0, 1e-12);
  // At Brewster's angle the p-polarised half vanishes: F = rs² / 2.
  const double tb = std::atan(1.45), c = std::cos(tb), ct = std::cos(kPi / 2 - tb);
  const double rs = (c - 1.45 * ct) / (c + 1.45 * ct);
  EXPECT_NEAR(CuticleCoat::fresnel(c, 1.45), 0.5 * rs * rs, 1e-12);
}

TEST(CuticleCoat, NoCoatAtIndexOne) {
  EXPECT_EQ(CuticleCoat::make(1.0, 0.3), nullptr);
  ASSERT_NE(CuticleCoat::make(1.45, 0.3), nullptr);
  EXPECT_DOUBLE_EQ(CuticleCoat::make(1.45, 0.3)->alpha(), 0.09);
  EXPECT_DOUBLE_EQ(CuticleCoat::make(1.45, 0.0)->alpha(), CuticleCoat::kMinAlpha);
}

TEST(CuticleCoat, AlbedoTableAgreesWithAnIndependentIntegral) {
  // E(μ) from the table (visible-normal quadrature, interpolated in μ) against the midpoint-rule
  // integral of f cos θ over the hemisphere, between the table's nodes.
  for (double roughness : {0.3, 0.6, 1.0}) {
    const CuticleCoat coat(1.45, roughness);
    for (double mu : {0.15, 0.5, 0.93}) {
      const Dir wo = at_angle(mu);
      const double direct = testing::hemisphere_integral(
          [&](const Dir& wi) { return coat.eval(wo, wi) * wi.z; }, 600);
      EXPECT_NEAR(coat.albedo(mu), direct, 0.004 * direct + 2e-5)
          << "roughness " << roughness << " μ " << mu;
    }
    // Ē against 2 ∫ E μ dμ by the midpoint rule over the interpolant's own values.
    double mean = 0.0;
    for (int k = 0; k < 1000; ++k)
      mean += 2.0 * coat.albedo((k + 0.5) / 1000) * (k + 0.5) / 1000 / 1000;
    EXPECT_NEAR(coat.mean_albedo(), mean, 1e-6);
    // A dielectric of index 1.45 reflects 3.4 % at normal incidence (less what a rough surface's
    // single scattering loses), and more towards grazing.
    EXPECT_LE(coat.albedo(1.0), 0.0338);
    EXPECT_GT(coat.albedo(1.0), roughness < 0.5 ? 0.033 : 0.01);
    EXPECT_GT(coat.albedo(0.1), 1.5 * coat.albedo(1.0));
  }
}

TEST(CuticleCoat, SamplingMatchesItsPdfAtSeveralRoughnesses) {
  for (double roughness : {0.2, 0.5, 1.0}) {
    const CuticleCoat coat(1.45, roughness);
    for (double mu : {0.3, 0.85}) {
      const Dir wo = at_angle(mu, 0.7);
      const auto r = testing::chi_square(
          [&](Rng& rng) {
            BsdfSample s;
            s.wi = coat.sample(wo, {rng.uniform(), rng.uniform()});
            s.pdf = s.wi.z > 0.0 ? coat.pdf(wo, s.wi) : 0.0;
            return s;
          },
          [&](const Dir& wi) { return coat.pdf(wo, wi); }, 400000, 9, 100, 64, 12);
      EXPECT_LT(r.chi2, testing::chi_square_critical(r.degrees_of_freedom))
          << "roughness " << roughness << " μ " << mu << " dof " << r.degrees_of_freedom;
      EXPECT_GT(r.degrees_of_freedom, 100);
    }
  }
}

TEST(CoatedLeafBsdf, SamplingMatchesItsPdfFromBothSides) {
  for (double roughness : {0.2, 0.45, 0.9}) {
    const CuticleCoat coat(1.45, roughness);
    const LeafBsdf bsdf{Rgb(0.06, 0.2, 0.04), Rgb(0.05, 0.18, 0.03), &coat};
    for (const Dir& wo :
         {glm::normalize(Dir(0.4, -0.2, 0.7)), glm::normalize(Dir(0.8, 0.3, -0.35))}) {
      const auto r = testing::chi_square(
          [&](Rng& rng) {
            return bsdf.sample(wo, {rng.uniform(), rng.uniform(), rng.uniform()});
          },
          [&](const Dir& wi) { return bsdf.pdf(wo, wi); }, 400000, 23, 100, 64, 12);
      EXPECT_LT(r.chi2, testing::chi_square_critical(r.degrees_of_freedom))
          << "roughness " << roughness << " wo.z " << wo.z;
    }
  }
}

TEST(CoatedLeafBsdf, SamplesCarryTheirOwnPdfAndValue) {
  const CuticleCoat coat(1.5, 0.3);
  const LeafBsdf bsdf{Rgb(0.1, 0.3, 0.05), Rgb(0.08, 0.25, 0.04), &coat};
  Rng rng(5);
  const Dir wo = glm::normalize(Dir(-0.3, 0.5, 0.6));
  int glossy = 0;
  for (int i = 0; i < 20000; ++i) {
    const BsdfSample s = bsdf.sample(wo, {rng.uniform(), rng.uniform(), rng.uniform()});
    if (s.pdf <= 0.0) continue;
    ASSERT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-9 * s.pdf);
    ASSERT_NEAR(s.value.y, bsdf.eval(wo, s.wi).y, 1e-12);
    glossy += (s.flags & kDiffuse) ? 0 : 1;
  }
  EXPECT_GT(glossy, 1000);  // the coat's own lobe is sampled
}

TEST(CoatedLeafBsdf, IsReciprocalOnBothSides) {
  const CuticleCoat coat(1.45, 0.35);
  const LeafBsdf bsdf{Rgb(0.3, 0.2, 0.1), Rgb(0.4, 0.5, 0.6), &coat};
  const Dir a = glm::normalize(Dir(0.1, 0.2, 0.9)), b = glm::normalize(Dir(-0.5, 0.3, -0.4));
  const Dir b_up(b.x, b.y, -b.z), c = glm::normalize(Dir(-0.2, -0.1, 0.95));
  for (const auto& [x, y] :
       {std::pair{a, b}, std::pair{a, b_up}, std::pair{a, c}, std::pair{-a, -c}}) {
    const Rgb f = bsdf.eval(x, y), g = bsdf.eval(y, x);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], g[k], 1e-12 * f[k]);
  }
}

TEST(CoatedLeafBsdf, AWhiteLeafScattersExactlyWhatArrivesAndADarkOneLess) {
  // R + T = 1 under the coat: the coat's reflection plus the diffuse lobes integrate to 1 at every
  // angle of incidence, on both faces; with R + T < 1 the leaf scatters E + (1 − E)(R + T) < 1.
  for (double roughness : {0.0, 0.3, 0.8}) {
    const CuticleCoat coat(1.45, roughness);
    const LeafBsdf white{Rgb(0.5, 0.6, 0.7), Rgb(0.5, 0.4, 0.3), &coat};
    const LeafBsdf dark{Rgb(0.06, 0.2, 0.04), Rgb(0.05, 0.18, 0.03), &coat};
    for (double mu : {0.08, 0.4, 0.97}) {
      for (double side : {1.0, -1.0}) {
        Dir wo = at_angle(mu, 1.1);
        wo.z *= side;
        const double e = coat.albedo(mu);
        // Transmission has no coat lobe: exactly (1 − E(μo)) T, at any roughness.
        const Rgb t = scattered(white, wo, side < 0);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(t[k], (1.0 - e) * white.transmittance[k], 2e-4);
        // Roughness 0 is a lobe narrower than the integration grid: the rest only where it
        // resolves.
        if (roughness < 0.1) continue;
        const Rgb w = scattered(white, wo, side > 0) + t;
        const Rgb d = scattered(dark, wo, side > 0) + scattered(dark, wo, side < 0);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(w[k], 1.0, 0.004) << "roughness " << roughness << " μ " << mu;
          EXPECT_NEAR(d[k], e + (1.0 - e) * (dark.reflectance[k] + dark.transmittance[k]), 0.004);
          EXPECT_LT(d[k], 1.0);
        }
      }
    }
  }
}

TEST(CoatedLeafBsdf, TheCoatReflectsWhiteAndIsStrongestAtTheMirrorDirection) {
  const CuticleCoat coat(1.45, 0.3);
  const LeafBsdf green{Rgb(0.06, 0.2, 0.04), Rgb(0.05, 0.18, 0.03), &coat};
  const LeafBsdf bare{green.reflectance, green.transmittance, nullptr};
  const Dir wo = at_angle(0.5, 0.0), mirror(-wo.x, -wo.y, wo.z), off = at_angle(0.9, 2.0);
  const Rgb highlight = green.eval(wo, mirror);
  const double e = coat.albedo(0.5),
               scale = (1.0 - e) * (1.0 - coat.albedo(0.5)) / (1.0 - coat.mean_albedo());
  const Rgb specular = highlight - bare.eval(wo, mirror) * scale;
  EXPECT_NEAR(specular.x, specular.y, 1e-12);
  EXPECT_NEAR(specular.y, specular.z, 1e-12);
  EXPECT_GT(specular.x, 10.0 * bare.eval(wo, mirror).y);  // a highlight, not a tint
  EXPECT_GT(green.eval(wo, mirror).x, green.eval(wo, off).x);
}

// Regularisation (`[render] regularize`): pbrt-v4's rule on GGX α = roughness², α < 0.3 →
// clamp(2α, 0.1, 0.3); coats already rougher are kept.
TEST(CuticleCoat, RegularizedRoughnessFollowsPbrtsRule) {
  EXPECT_NEAR(CuticleCoat::regularized_roughness(0.0), std::sqrt(0.1), 1e-12);   // mirror → 0.1
  EXPECT_NEAR(CuticleCoat::regularized_roughness(0.2), std::sqrt(0.1), 1e-12);   // 2 × 0.04
  EXPECT_NEAR(CuticleCoat::regularized_roughness(0.3), std::sqrt(0.18), 1e-12);  // 2 × 0.09
  EXPECT_NEAR(CuticleCoat::regularized_roughness(0.35), std::sqrt(0.245), 1e-12);
  EXPECT_NEAR(CuticleCoat::regularized_roughness(0.5), std::sqrt(0.3), 1e-12);  // 0.5 → 0.3
  EXPECT_EQ(CuticleCoat::regularized_roughness(0.6), 0.6);                      // α 0.36
  EXPECT_EQ(CuticleCoat::regularized_roughness(1.0), 1.0);
}

// A leaf takes its regularised coat only on a regularised path, and only if it has one.
TEST(CuticleCoat, ALeafUsesItsRegularizedCoatOnlyWhenThePathAsks) {
  const CuticleCoat sharp(1.45, 0.35), rough(1.45, CuticleCoat::regularized_roughness(0.35));
  LeafMaterial m;
  m.cuticle = &sharp;
  m.regularized = &rough;
  SurfacePoint p;
  EXPECT_EQ(std::get<LeafBsdf>(m.bsdf(p).lobes).coat, &sharp);
  p.regularize = true;
  EXPECT_EQ(std::get<LeafBsdf>(m.bsdf(p).lobes).coat, &rough);
  m.regularized = nullptr;
  EXPECT_EQ(std::get<LeafBsdf>(m.bsdf(p).lobes).coat, &sharp);
}

}  // namespace arbor::materials
