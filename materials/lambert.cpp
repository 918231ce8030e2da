// Lambertian BSDF: cosine-weighted sampling, so value·cos/pdf = albedo exactly.
#include "materials/lambert.h"

#include <algorithm>
#include <cmath>

#include "common/math.h"

namespace arbor::mat {

Dir sample_cosine_hemisphere(const glm::dvec2& u) {
  // The concentric map of the square to the disk, lifted to the hemisphere (Malley).
  const glm::dvec2 d = concentric_disk(u.x, u.y);
  const double x = d.x, y = d.y;
  return {x, y, std::sqrt(std::max(0.0, 1.0 - x * x - y * y))};
}

Rgb Lambert::eval(const Dir& wo, const Dir& wi) const {
  if (!same_hemisphere(wo, wi)) return Rgb(0.0);
  return albedo / kPi;
}

double Lambert::pdf(const Dir& wo, const Dir& wi) const {
  if (!same_hemisphere(wo, wi)) return 0.0;
  return std::fabs(wi.z) / kPi;
}

BsdfSample Lambert::sample(const Dir& wo, const glm::dvec2& u) const {
  BsdfSample s;
  Dir wi = sample_cosine_hemisphere(u);
  if (wo.z < 0.0) wi.z = -wi.z;  // reflect on the side the ray came from
  s.wi = wi;
  s.pdf = pdf(wo, wi);
  s.value = s.pdf > 0.0 ? eval(wo, wi) : Rgb(0.0);
  s.flags = kReflection | kDiffuse;
  return s;
}

}  // namespace arbor::mat
