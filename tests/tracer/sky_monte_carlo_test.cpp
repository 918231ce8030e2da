// The Monte Carlo simulation of the atmosphere (sky_monte_carlo.h) against the Nishita model: with
// single scattering only, the two compute the same integral by unrelated methods (delta tracking
// and sampled directions against a quadrature along the view ray) and must agree within the
// simulation's noise; with every order and a bright ground the simulated sky is brighter, as
// multiple scattering makes the real one.
#include "tracer/lights/sky_monte_carlo.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "common/math.h"

namespace arbor::tracer {

namespace {

glm::dvec3 direction(double elevation_deg, double azimuth_deg) {
  const double e = radians(elevation_deg), a = radians(azimuth_deg);
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

// 21 directions at three sun elevations: the zenith, the horizon (5°) towards, across and away
// from the sun, 30° up at 45° and 135° from it, and 15° from the sun.
struct Case {
  double sun_elevation, elevation, azimuth;
};
std::vector<Case> cases() {
  std::vector<Case> c;
  for (double sun : {10.0, 40.0, 60.0}) {
    for (const auto& [e, a] : std::vector<std::pair<double, double>>{
             {90, 0}, {5, 0}, {5, 90}, {5, 180}, {30, 45}, {30, 135}, {sun + 15.0, 0}})
      c.push_back({sun, std::min(e, 90.0), a});
  }
  return c;
}

}  // namespace

TEST(SkyMonteCarlo, SingleScatteringAgreesWithNishitaInTwentyOneDirections) {
  const Atmosphere air{1.0, 3.0, 1.0, 0.0};  // the default scene's dust
  SkyMonteCarloOptions o;
  o.single_scattering = true;
  o.paths = 40000;
  int i = 0;
  for (const Case& c : cases()) {
    const glm::dvec3 sun = direction(c.sun_elevation, 0.0),
                     view = direction(c.elevation, c.azimuth);
    const NishitaSky model(air, sun, 1.0);
    const glm::dvec3 exact = model.radiance_xyz(view, 512);
    o.seed = static_cast<std::uint64_t>(++i);
    const SkyMonteCarloResult mc = simulate_sky_radiance(model, air, sun, view, o);
    for (int k = 0; k < 3; ++k) {
      SCOPED_TRACE(testing::Message()
                   << "sun " << c.sun_elevation << "°, view " << c.elevation << "°/" << c.azimuth
                   << "°, component " << k << ": model " << exact[k] << ", simulated " << mc.xyz[k]
                   << " ± " << mc.standard_error[k]);
      EXPECT_LT(mc.standard_error[k], 0.03 * exact[k]);
      EXPECT_NEAR(mc.xyz[k], exact[k], 4.0 * mc.standard_error[k] + 0.005 * exact[k]);
    }
  }
}

}  // namespace arbor::tracer

namespace arbor::tracer {

// Every order of scattering and a ground that reflects: the sky is brighter than single scattering
// gives — most where the path is long (the horizon) — and the surplus grows with the ground's
// albedo; in an optically thin atmosphere (1 % of the air and dust) the orders beyond the first
// vanish and the two agree.
TEST(SkyMonteCarlo, MultipleScatteringAndTheGroundBrightenTheSky) {
  const glm::dvec3 sun = direction(40.0, 0.0);
  SkyMonteCarloOptions o;
  o.paths = 40000;
  auto y = [&](const Atmosphere& air, const glm::dvec3& view, bool single, double albedo) {
    const NishitaSky model(air, sun, 1.0);
    SkyMonteCarloOptions p = o;
    p.single_scattering = single;
    p.ground_albedo = albedo;
    const SkyMonteCarloResult r = simulate_sky_radiance(model, air, sun, view, p);
    std::printf("  %s albedo %.1f view z %.2f: Y %.5g ± %.2g (%.2f events)\n",
                single ? "single" : "all   ", albedo, view.z, r.xyz.y, r.standard_error.y,
                r.mean_orders);
    return r;
  };
  const Atmosphere air{1.0, 3.0, 1.0, 0.0};
  for (const glm::dvec3& view : {direction(90, 0), direction(5, 90), direction(5, 180)}) {
    const SkyMonteCarloResult one = y(air, view, true, 0.0);
    const SkyMonteCarloResult all = y(air, view, false, 0.0);
    const SkyMonteCarloResult ground = y(air, view, false, 0.3);
    EXPECT_GT(all.xyz.y - one.xyz.y, 4.0 * (all.standard_error.y + one.standard_error.y));
    EXPECT_GT(ground.xyz.y - all.xyz.y, 4.0 * (all.standard_error.y + ground.standard_error.y));
  }
  const Atmosphere thin{0.01, 0.01, 1.0, 0.0};
  const SkyMonteCarloResult one = y(thin, direction(5, 90), true, 0.0);
  const SkyMonteCarloResult all = y(thin, direction(5, 90), false, 0.0);
  EXPECT_NEAR(all.xyz.y, one.xyz.y,
              4.0 * (all.standard_error.y + one.standard_error.y) + 0.01 * one.xyz.y);
}

}  // namespace arbor::tracer
