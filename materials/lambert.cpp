// Lambertian BSDF: cosine-weighted sampling, so value·cos/pdf = albedo exactly.
#include "materials/lambert.h"

#include <algorithm>
#include <cmath>

namespace arbor::mat {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Dir sample_cosine_hemisphere(const glm::dvec2& u) {
  // Concentric mapping of the square to the disk (Shirley & Chiu), then lift to the hemisphere.
  const double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
  double r = 0.0, phi = 0.0;
  if (a != 0.0 || b != 0.0) {
    if (std::fabs(a) > std::fabs(b)) {
      r = a;
      phi = (kPi / 4.0) * (b / a);
    } else {
      r = b;
      phi = (kPi / 2.0) - (kPi / 4.0) * (a / b);
    }
  }
  const double x = r * std::cos(phi), y = r * std::sin(phi);
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
