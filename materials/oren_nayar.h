// Oren–Nayar rough diffuse reflection (the qualitative model, Oren & Nayar 1994 eq. 30) as the
// option for bark; sigma is the standard deviation of facet slopes in radians (0: Lambert).
#pragma once

#include "materials/bsdf.h"

namespace arbor::materials {

struct OrenNayar {
  Rgb albedo{0.5};
  double sigma = 0.0;

  Rgb eval(const Dir& wo, const Dir& wi) const;
  double pdf(const Dir& wo, const Dir& wi) const;  // cosine-weighted
  // u.y and u.z the direction (u.x, a lobe choice, is unused: one lobe).
  BsdfSample sample(const Dir& wo, const glm::dvec3& u) const;
  unsigned flags() const { return kReflection | kDiffuse; }
};

}  // namespace arbor::materials
