// Lambertian reflection: f = albedo / π on the side of the normal the light comes from.
#pragma once

#include "materials/bsdf.h"

namespace arbor::mat {

struct Lambert {
  Rgb albedo{0.5};

  Rgb eval(const Dir& wo, const Dir& wi) const;
  double pdf(const Dir& wo, const Dir& wi) const;
  BsdfSample sample(const Dir& wo, const glm::dvec2& u) const;
};

}  // namespace arbor::mat
