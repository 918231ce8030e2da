// A thin two-sided leaf: diffuse reflection on the side the light arrives from and diffuse
// transmission to the other side, optionally under a waxy cuticle (cuticle.h) that reflects
// specularly on both faces. The caller picks front or back reflectance by the side hit.
#pragma once

#include "materials/bsdf.h"
#include "materials/cuticle.h"

namespace arbor::materials {

struct LeafBsdf {
  Rgb reflectance{0.1};               // of the side the ray came from
  Rgb transmittance{0.1};             // R + T ≤ 1 per channel
  const CuticleCoat* coat = nullptr;  // null: no cuticle (the bare diffuse leaf)

  Rgb eval(const Dir& wo, const Dir& wi) const;
  double pdf(const Dir& wo, const Dir& wi) const;
  // u.x chooses the lobe (the coat's reflection with probability ∝ its share of what the leaf
  // scatters, then reflect with probability ∝ luminance of R), u.y and u.z the direction.
  BsdfSample sample(const Dir& wo, const glm::dvec3& u) const;
  double reflect_probability() const;  // of the diffuse base: reflect rather than transmit
  double coat_probability(const Dir& wo) const;  // 0 without a coat
  unsigned flags() const { return kReflection | kTransmission | kDiffuse | (coat ? kGlossy : 0u); }
};

}  // namespace arbor::materials
