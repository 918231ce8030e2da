// The sun's limb darkening: its disk is brighter at the centre than at the edge, more so in the
// blue, because near the limb the line of sight ends in higher, cooler layers of the photosphere.
// Neckel 2005's analytic fit (Solar Physics 229, 13–33) of the centre-to-limb variation measured
// by Neckel & Labs 1994 (Solar Physics 153, 91–114): I(λ, μ) / I(λ, 1) = Σₖ Aₖ(λ) μᵏ, k = 0 … 5,
// with A₀ = a₀₀ + a₀₁/λ, Aₖ = aₖ₀ + aₖ₅/λ⁵ (k ≥ 2) and A₁ making the sum 1 at μ = 1 (λ in µm; three
// wavelength ranges, the middle one extended over its 373–385 nm gap), μ the cosine of the angle
// on the solar surface.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "imaging/color.h"

namespace arbor::tracer {

// I(μ) / I(1) at `nm` nanometres (300 … 1100).
double solar_limb_darkening(double nm, double mu);

// The disk's mean of I(μ) / I(1) (over its area: ∫₀¹ I(μ)/I(1) 2μ dμ).
double solar_limb_mean(double nm);

// The disk's radiance relative to its mean in the rendering space, per channel, at `steps`
// points s = θ / α from the centre (0) to the limb (1), for the sun's spectrum (nishita.h) seen
// through the CIE 1931 observer: what multiplies the uniform disk's radiance so that its irradiance
// is kept.
std::vector<glm::vec3> solar_limb_profile(const imaging::ColorTransform& xyz_to_linear, int steps);

}  // namespace arbor::tracer
