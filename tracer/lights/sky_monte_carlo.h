// An independent check of the sky models: sunlight traced backwards by Monte Carlo from the
// observer through the spherical atmosphere of nishita.h (its density profiles, coefficients and
// phase functions — the atmosphere's definition, not any model's method), every order of
// scattering, with a Lambertian ground. It shares no code with the models: its free paths are
// sampled by delta tracking against a majorant, its transmittance towards the sun is its own
// quadrature, and its directions are sampled from the phase functions. Slow (seconds a
// direction); for tests and benches, not for rendering. docs/rendering.md, "Sky", states the
// method.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "tracer/lights/nishita.h"

namespace arbor::tracer {

struct SkyMonteCarloOptions {
  int paths = 20000;               // paths traced for the direction
  bool single_scattering = false;  // only the first scattering (and no ground): Nishita's model
  int max_orders = 0;  // > 0: only light that has met at most this many events (ground included)
  double ground_albedo = 0.0;  // Lambertian ground reflectance (the same at every wavelength)
  std::uint64_t seed = 1;
};

struct SkyMonteCarloResult {
  glm::dvec3 xyz{0.0};             // the sky's radiance in the direction, CIE XYZ
  glm::dvec3 standard_error{0.0};  // of each component, from the paths' spread
  double mean_orders = 0.0;        // scattering events a path had on average (ground included)
};

// The radiance of the sky (without the sun's disk) seen by an observer at `atmosphere.altitude`
// in direction `view` (unit, z up), for a sun in `sun_direction` of extraterrestrial irradiance
// `sun_irradiance` (CIE Y) — the quantity NishitaSky::radiance_xyz computes. The spectral
// weights (the sun's spectrum × colour matching functions) are the model's, so the two are
// compared in the same units; wavelengths are sampled in proportion to them.
SkyMonteCarloResult simulate_sky_radiance(const NishitaSky& units, const Atmosphere& atmosphere,
                                          const glm::dvec3& sun_direction, const glm::dvec3& view,
                                          const SkyMonteCarloOptions& options);

}  // namespace arbor::tracer
