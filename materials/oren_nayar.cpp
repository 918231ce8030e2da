// f = ρ/π (A + B max(0, cos(φi − φo)) sin α tan β), A = 1 − σ²/(2(σ² + 0.33)),
// B = 0.45 σ²/(σ² + 0.09), α = max(θi, θo), β = min(θi, θo).
#include "materials/oren_nayar.h"

#include <algorithm>
#include <cmath>
#include "common/math.h"

namespace arbor::materials {

Rgb OrenNayar::eval(const Dir& wo, const Dir& wi) const {
  if (!same_hemisphere(wo, wi)) return Rgb(0.0);
  const double s2 = sigma * sigma;
  const double a = 1.0 - s2 / (2.0 * (s2 + 0.33)), b = 0.45 * s2 / (s2 + 0.09);
  const double cos_i = std::fabs(wi.z), cos_o = std::fabs(wo.z);
  const double sin_i = std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
  const double sin_o = std::sqrt(std::max(0.0, 1.0 - cos_o * cos_o));
  double cos_dphi = 0.0;
  if (sin_i > 1e-6 && sin_o > 1e-6) {
    cos_dphi = std::max(0.0, (wi.x * wo.x + wi.y * wo.y) / (sin_i * sin_o));
  }
  double sin_alpha, tan_beta;
  if (cos_i > cos_o) {  // θi < θo: α = θo, β = θi
    sin_alpha = sin_o;
    tan_beta = sin_i / cos_i;
  } else {
    sin_alpha = sin_i;
    tan_beta = cos_o > 0.0 ? sin_o / cos_o : 0.0;
  }
  return albedo / kPi * (a + b * cos_dphi * sin_alpha * tan_beta);
}

double OrenNayar::pdf(const Dir& wo, const Dir& wi) const {
  return same_hemisphere(wo, wi) ? std::fabs(wi.z) / kPi : 0.0;
}

BsdfSample OrenNayar::sample(const Dir& wo, const glm::dvec3& u) const {
  BsdfSample s;
  Dir wi = sample_cosine_hemisphere(glm::dvec2(u.y, u.z));
  if (wo.z < 0.0) wi.z = -wi.z;
  s.wi = wi;
  s.pdf = pdf(wo, wi);
  s.value = eval(wo, wi);
  s.flags = flags();
  return s;
}

}  // namespace arbor::materials
