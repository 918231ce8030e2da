// The sun's limb darkening (tracer/lights/limb_darkening.h): Neckel 2005's analytic fit against
// the independent polynomial fits of Neckel & Labs 1994 (their table, transcribed here), the
// profile in the rendering space, and the sky's sun keeping its irradiance.
#include "tracer/lights/limb_darkening.h"

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "spec/scene_desc.h"
#include "scene/render_input.h"
#include "test_world.h"
#include "tracer/lights/nishita.h"
#include "tracer/lights/sky.h"

namespace arbor::tracer {

// Neckel & Labs 1994's fifth-degree fits at three of their wavelengths (nm, A0 … A5), against
// which the 2005 analytic form must agree within 1.5 % of I(1) from μ = 0.1 to 1.
TEST(LimbDarkening, NeckelsAnalyticFitAgreesWithHisTabulatedFits) {
  const std::array<std::array<double, 7>, 3> table{{
      {443.885, 0.16220, 1.24893, -0.92165, 0.89978, -0.50148, 0.11220},
      {559.950, 0.26892, 1.34319, -1.58427, 1.91271, -1.31350, 0.37295},
      {700.875, 0.37885, 1.25553, -1.70908, 2.19647, -1.59554, 0.47378},
  }};
  for (const auto& row : table) {
    double total = 0.0;
    for (int k = 1; k < 7; ++k) total += row[static_cast<std::size_t>(k)];
    for (double mu : {0.1, 0.3, 0.5, 0.8, 1.0}) {
      double tabulated = 0.0, p = 1.0;
      for (int k = 1; k < 7; ++k, p *= mu) tabulated += row[static_cast<std::size_t>(k)] * p;
      EXPECT_NEAR(solar_limb_darkening(row[0], mu), tabulated / total, 0.015)
          << row[0] << " nm, mu " << mu;
    }
  }
  // Darker towards the limb, and more so in the blue.
  EXPECT_LT(solar_limb_darkening(450.0, 0.3), solar_limb_darkening(650.0, 0.3));
  EXPECT_LT(solar_limb_darkening(550.0, 0.2), solar_limb_darkening(550.0, 0.6));
}

// In the rendering space: the disk's area mean of the profile is 1 in every channel (the
// irradiance is kept), the centre is brighter than the mean and the limb darker, the blue limb
// darkest.
TEST(LimbDarkening, TheProfileKeepsTheDisksMeanAndDarkensTheBlueMost) {
  const std::vector<glm::vec3> p = solar_limb_profile(xyz_to_scene_linear(), 65);
  glm::dvec3 mean(0.0);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    // ∫ profile(s) 2s ds by the trapezoid rule on each interval.
    const double s0 = double(i) / 64, s1 = double(i + 1) / 64;
    mean += 0.5 * (glm::dvec3(p[i]) * 2.0 * s0 + glm::dvec3(p[i + 1]) * 2.0 * s1) * (s1 - s0);
  }
  std::printf("  centre %.3f %.3f %.3f, limb %.3f %.3f %.3f, mean %.4f %.4f %.4f\n", p[0].x, p[0].y,
              p[0].z, p.back().x, p.back().y, p.back().z, mean.x, mean.y, mean.z);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mean[c], 1.0, 0.003) << c;
    EXPECT_GT(p[0][c], 1.1f) << c;
    EXPECT_LT(p.back()[c], 0.6f) << c;
  }
  EXPECT_LT(p.back().z, p.back().x);
}

// The sky's sun: the irradiance its radiance gives, integrated over the disk (200 rings), is the
// sun's irradiance within 0.1 %; its centre is brighter than its mean radiance.
TEST(LimbDarkening, TheSunKeepsItsIrradiance) {
  const spec::SunDesc sun{true, 40.0, 30.0, 3.0, 0.53};
  spec::SkyDesc none;
  none.model = spec::SkyModel::None;
  const Sky sky(none, sun, xyz_to_scene_linear(), 16);
  const glm::vec3 w = sky.sun_direction();
  const glm::vec3 a = glm::normalize(glm::cross(w, glm::vec3(0, 0, 1))), b = glm::cross(w, a);
  const double alpha = radians(0.5 * sun.angular_diameter);
  glm::dvec3 e(0.0);
  constexpr int kRings = 200, kSectors = 64;
  for (int i = 0; i < kRings; ++i) {
    const double theta = alpha * (i + 0.5) / kRings;
    for (int j = 0; j < kSectors; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / kSectors;
      const glm::vec3 d = glm::normalize(
          w * static_cast<float>(std::cos(theta)) +
          (a * static_cast<float>(std::cos(phi)) + b * static_cast<float>(std::sin(phi))) *
              static_cast<float>(std::sin(theta)));
      e += glm::dvec3(sky.sun_radiance(d)) * std::cos(theta) * std::sin(theta) * (alpha / kRings) *
           (2.0 * kPi / kSectors);
    }
  }
  std::printf("  irradiance %.5f %.5f %.5f of 3\n", e.x, e.y, e.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], 3.0, 0.001 * 3.0) << c;
  EXPECT_GT(sky.sun_radiance(w).y, 1.1f * sky.sun_radiance().y);
}

}  // namespace arbor::tracer

namespace arbor::tracer {

// The tabulated solar spectrum: the table's values at its nodes (Preetham et al. 1999's 380, 550
// and 750 nm), linear between them, its last slope continued to 780 nm; and the sun's colour
// near a 5800 K black body's (CIE 1931 x, y within 0.01), as the measured sun is.
TEST(SolarSpectrum, IsTheTableAndLooksLikeTheSun) {
  EXPECT_DOUBLE_EQ(atmosphere::solar_spectrum(380.0), 165.5);
  EXPECT_DOUBLE_EQ(atmosphere::solar_spectrum(550.0), 255.0);
  EXPECT_DOUBLE_EQ(atmosphere::solar_spectrum(750.0), 182.6);
  EXPECT_NEAR(atmosphere::solar_spectrum(555.0), 0.5 * (255.0 + 250.6), 1e-9);
  EXPECT_NEAR(atmosphere::solar_spectrum(780.0), 182.6 - 3.0 * (186.3 - 182.6), 1e-9);
  glm::dvec3 sun(0.0), body(0.0);
  for (int nm = 380; nm <= 780; ++nm) {
    const double l = nm * 1e-9;
    sun += atmosphere::solar_spectrum(nm) * NishitaSky::cie_xyz_bar(nm);
    body += NishitaSky::cie_xyz_bar(nm) /
            (l * l * l * l * l * (std::exp(1.4387769e-2 / (l * 5800.0)) - 1.0));
  }
  const double sx = sun.x / (sun.x + sun.y + sun.z), sy = sun.y / (sun.x + sun.y + sun.z);
  const double bx = body.x / (body.x + body.y + body.z), by = body.y / (body.x + body.y + body.z);
  std::printf("  sun (%.4f, %.4f), 5800 K (%.4f, %.4f)\n", sx, sy, bx, by);
  EXPECT_NEAR(sx, bx, 0.01);
  EXPECT_NEAR(sy, by, 0.01);
}

}  // namespace arbor::tracer
