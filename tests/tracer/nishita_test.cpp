// Tests of the Nishita sky: its constants against published values, optically thin radiance and
// transmittance against closed forms, the colours a clear sky has (zenith bluer than the horizon,
// a deep blue zenith at 45°, a red low sun), the importance-sampled map's irradiance against an
// independent integration of the model, and the sun's light through an empty atmosphere.
#include "tracer/lights/nishita.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/math.h"
#include "tracer/lights/sky.h"
#include "tracer/test_world.h"

namespace arbor::tracer {

namespace {

glm::dvec3 sun_at(double elevation_deg) {
  const double e = radians(elevation_deg);
  return {std::cos(e), 0.0, std::sin(e)};
}

glm::dvec3 rec709(const glm::dvec3& xyz) {
  float c[3] = {float(xyz.x), float(xyz.y), float(xyz.z)};
  xyz_to_scene_linear()(c);  // arbor's scene_linear is linear Rec.709
  return {c[0], c[1], c[2]};
}

Sky nishita_sky(double elevation, const spec::SkyDesc& base = {}, int width = 256) {
  spec::SkyDesc sky = base;
  sky.model = spec::SkyModel::Nishita;
  spec::SunDesc sun;
  sun.elevation = elevation;
  sun.azimuth = 0.0;
  return Sky(sky, sun, xyz_to_scene_linear(), width);
}

}  // namespace

TEST(Nishita, RayleighAndOzoneConstantsAreThePublishedOnes) {
  // Rayleigh scattering of sea-level air: optical depth 0.0973 at 550 nm and 0.364 at 400 nm for
  // the whole atmosphere (Bucholtz 1995), whose column is p0 / (m g) = 2.148e29 molecules m⁻²,
  // 8.43 km of sea-level air (the model's exponential profile of 8 km holds 5 % less).
  EXPECT_NEAR(NishitaSky::rayleigh_scattering(550.0) * 8434.0, 0.0973, 0.002);
  EXPECT_NEAR(NishitaSky::rayleigh_scattering(400.0) * 8434.0, 0.364, 0.008);
  // ≈ λ⁻⁴ (a little steeper, by the dispersion of air).
  const double ratio =
      NishitaSky::rayleigh_scattering(440.0) / NishitaSky::rayleigh_scattering(680.0);
  EXPECT_GT(ratio, std::pow(680.0 / 440.0, 4.0));
  EXPECT_LT(ratio, 1.08 * std::pow(680.0 / 440.0, 4.0));
  // The Chappuis band peaks near 600 nm at about 5e-21 cm² and is weak in the blue.
  EXPECT_NEAR(NishitaSky::ozone_cross_section(600.0), 5e-25, 1e-27);
  EXPECT_LT(NishitaSky::ozone_cross_section(440.0), 0.01 * NishitaSky::ozone_cross_section(600.0));
  // The colour matching functions' peaks: ȳ(555) ≈ 1, x̄(600) ≈ 1.06, z̄(445) ≈ 1.78.
  EXPECT_NEAR(NishitaSky::cie_xyz_bar(555.0).y, 1.0, 0.01);
  EXPECT_NEAR(NishitaSky::cie_xyz_bar(600.0).x, 1.06, 0.01);
  EXPECT_NEAR(NishitaSky::cie_xyz_bar(445.0).z, 1.78, 0.03);
}

TEST(Nishita, AnEmptyAtmosphereLetsTheSunThroughWhiteAndHasNoSky) {
  spec::SkyDesc empty;
  empty.air_density = empty.dust_density = empty.ozone_density = 0.0;
  const Sky sky = nishita_sky(30.0, empty, 64);
  ASSERT_TRUE(sky.has_sun());
  const glm::vec3 e = sky.sun_irradiance_color();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], 3.0f, 3e-4f);  // [sun] irradiance, white
  EXPECT_EQ(sky.radiance(glm::normalize(glm::vec3(0.3f, 0.2f, 0.5f))), glm::vec3(0.0f));
  EXPECT_TRUE(sky.empty());
}

TEST(Nishita, ThinAirScattersAndAttenuatesAsTheClosedForms) {
  // Air only, 1 % of it: single scattering is optically thin, so the zenith with the sun at the
  // zenith is L(λ) = E(λ) β(λ) × 0.01 H (1 − e^(−60 km / H)) × 3/(8π) (Rayleigh's phase forward),
  // attenuated by e^(−τ) on the way (τ ≈ 0.001 here, kept in the closed form).
  Atmosphere air;
  air.air_density = 0.01;
  air.dust_density = air.ozone_density = 0.0;
  const NishitaSky model(air, {0.0, 0.0, 1.0}, 3.0);
  const double h = 8000.0, column = 0.01 * h * (1.0 - std::exp(-60e3 / h));
  glm::dvec3 expected(0.0), space(0.0);
  // The extraterrestrial spectrum the model uses is the tabulated solar one scaled to Y = 3.
  double y = 0.0;
  for (int k = 0; k < NishitaSky::kWavelengths; ++k) {
    const double nm = NishitaSky::wavelength(k);
    y += NishitaSky::cie_xyz_bar(nm).y * atmosphere::solar_spectrum(nm);
  }
  for (int k = 0; k < NishitaSky::kWavelengths; ++k) {
    const double nm = NishitaSky::wavelength(k);
    const double s = 3.0 / y * atmosphere::solar_spectrum(nm);
    const double beta = NishitaSky::rayleigh_scattering(nm), tau = beta * column;
    expected +=
        s * beta * column * 3.0 / (8.0 * kPi) * std::exp(-tau) * NishitaSky::cie_xyz_bar(nm);
    space += s * NishitaSky::cie_xyz_bar(nm);
    EXPECT_NEAR(model.transmittance({0.0, 0.0, 1.0}, k), std::exp(-tau), 1e-5 * tau);
  }
  EXPECT_NEAR(space.y, 3.0, 1e-9);
  const glm::dvec3 zenith = model.radiance_xyz({0.0, 0.0, 1.0}, 2048);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(zenith[c], expected[c], 0.002 * expected[c]) << "channel " << c;
  // The default quadrature (32 steps) within 0.3 % of it.
  EXPECT_NEAR(model.radiance_xyz({0.0, 0.0, 1.0}).y, expected.y, 0.003 * expected.y);
}

TEST(Nishita, TheDefaultQuadratureHasConverged) {
  const NishitaSky model(Atmosphere{}, sun_at(20.0), 3.0);
  for (const glm::dvec3& d : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(-1, 0.3, 0.02)),
                              glm::normalize(glm::dvec3(1, 0.05, 0.4))}) {
    const glm::dvec3 a = model.radiance_xyz(d), b = model.radiance_xyz(d, 2048);
    EXPECT_NEAR(a.y, b.y, 0.005 * b.y);
  }
}

TEST(Nishita, TheZenithIsBluerThanTheHorizonAndDeepBlueAt45Degrees) {
  // As rendered: the map, white-balanced so that the sun outside the atmosphere is white.
  const Sky sky = nishita_sky(45.0, {}, 512);
  const glm::vec3 zenith = sky.radiance({0.0f, 0.0f, 1.0f});
  const glm::vec3 horizon = sky.radiance(glm::normalize(glm::vec3(-1.0f, 0.0f, 0.03f)));
  EXPECT_GT(zenith.z / zenith.x, horizon.z / horizon.x);
  // The bound: the zenith's blue / red in linear Rec.709 at least 3 (measured 3.07).
  EXPECT_GE(zenith.z / zenith.x, 3.0f);
  EXPECT_GT(zenith.z, zenith.y);
  // Before the white balance the model's own XYZ is a little warmer (a 5778 K sun), still blue.
  const NishitaSky model(Atmosphere{}, sun_at(45.0), 3.0);
  const glm::dvec3 raw = rec709(model.radiance_xyz({0.0, 0.0, 1.0}));
  EXPECT_GT(raw.z / raw.x, 2.4);
}

TEST(Nishita, ALowSunIsRedAndDimAndSoIsTheSkyAroundIt) {
  const Sky high = nishita_sky(45.0, {}, 128), low = nishita_sky(2.0, {}, 128);
  const glm::vec3 sun = low.sun_irradiance_color();
  EXPECT_GT(sun.x, 1.5f * sun.y);
  EXPECT_GT(sun.y, sun.z);
  EXPECT_LT(sun.y, 0.2f * high.sun_irradiance_color().y);  // dim: through ~20 air masses
  const glm::vec3 around = low.radiance(glm::normalize(glm::vec3(1.0f, 0.05f, 0.05f)));
  EXPECT_GT(around.x, around.z);
  EXPECT_GT(around.x, around.y);
  // High: the sun is near white (a little yellow) and far brighter than the low one.
  const glm::vec3 white = high.sun_irradiance_color();
  EXPECT_GT(white.z, 0.75f * white.x);
  EXPECT_LT(white.z, white.x);
  // Below the horizon: no sun disk, a dim twilight sky.
  const Sky night = nishita_sky(-4.0, {}, 64);
  EXPECT_FALSE(night.has_sun());
  EXPECT_FALSE(night.empty());
  EXPECT_LT(night.irradiance_up().y, 0.05f * low.irradiance_up().y);
}

TEST(Nishita, TheMapsIrradianceIsTheModelsIntegratedIndependently) {
  // Sky::irradiance_up sums the lat-long map's texels; here the model itself is integrated over
  // the hemisphere by the midpoint rule in (cos θ, φ) on a different grid.
  for (double elevation : {45.0, 8.0}) {
    const Sky sky = nishita_sky(elevation, {}, 256);
    const NishitaSky model(Atmosphere{}, sun_at(elevation), 3.0);
    // The map's white balance (the sun outside the atmosphere is white): the same as Sky's.
    const glm::dvec3 space = rec709(model.extraterrestrial_xyz());
    const glm::dvec3 balance = model.extraterrestrial_xyz().y / space;
    const int n = 48, m = 96;
    glm::dvec3 e(0.0);
    for (int i = 0; i < n; ++i) {
      const double z = (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
      for (int j = 0; j < m; ++j) {
        const double phi = kTwoPi * (j + 0.5) / m;
        const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
        e += rec709(model.radiance_xyz(d)) * balance * z * (1.0 / n) * (kTwoPi / m);
      }
    }
    const glm::vec3 map = sky.irradiance_up();
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(map[c], e[c], 0.01 * e[c]) << "elevation " << elevation << " channel " << c;
  }
}

TEST(Nishita, DensitiesAndAltitudeChangeTheSkyTheWayTheyShould) {
  const NishitaSky standard(Atmosphere{}, sun_at(30.0), 3.0);
  Atmosphere dusty, high, no_ozone;
  dusty.dust_density = 8.0;
  high.altitude = 3000.0;
  no_ozone.ozone_density = 0.0;
  const glm::dvec3 up = glm::normalize(glm::dvec3(-0.3, 0.4, 0.8));
  const glm::dvec3 s = rec709(standard.radiance_xyz(up));
  const glm::dvec3 d = rec709(NishitaSky(dusty, sun_at(30.0), 3.0).radiance_xyz(up));
  const glm::dvec3 h = rec709(NishitaSky(high, sun_at(30.0), 3.0).radiance_xyz(up));
  const glm::dvec3 o = rec709(NishitaSky(no_ozone, sun_at(30.0), 3.0).radiance_xyz(up));
  EXPECT_LT(d.z / d.x, s.z / s.x);  // haze whitens the sky
  EXPECT_LT(h.y, s.y);              // less air above: darker
  EXPECT_LT(o.z / o.x, s.z / s.x);  // ozone takes red and green, not blue
  EXPECT_GT(NishitaSky(high, sun_at(30.0), 3.0).sun_irradiance_xyz().y,
            standard.sun_irradiance_xyz().y);
}

}  // namespace arbor::tracer
