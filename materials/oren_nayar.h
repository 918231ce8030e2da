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
  BsdfSample sample(const Dir& wo, const glm::dvec2& u) const;
};

}  // namespace arbor::materials
