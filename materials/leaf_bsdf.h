// A thin two-sided leaf: diffuse reflection on the side the light arrives from and diffuse
// transmission to the other side. The caller picks front or back reflectance by the side hit.
#pragma once

#include "materials/bsdf.h"

namespace arbor::mat {

struct LeafBsdf {
  Rgb reflectance{0.1};    // of the side the ray came from
  Rgb transmittance{0.1};  // R + T ≤ 1 per channel

  Rgb eval(const Dir& wo, const Dir& wi) const;
  double pdf(const Dir& wo, const Dir& wi) const;
  // u.x chooses the lobe (reflect with probability ∝ luminance of R), u.y and u.z the direction.
  BsdfSample sample(const Dir& wo, const glm::dvec3& u) const;
  double reflect_probability() const;
};

}  // namespace arbor::mat
