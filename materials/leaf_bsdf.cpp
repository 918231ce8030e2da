// Leaf BSDF: f = R/π in the hemisphere of wo, T/π in the other; lobes chosen by luminance.
#include "materials/leaf_bsdf.h"

#include <cmath>
#include "common/math.h"

namespace arbor::mat {

namespace {
double luminance(const Rgb& c) { return arbor::luminance(c.x, c.y, c.z); }
}  // namespace

double LeafBsdf::reflect_probability() const {
  const double r = luminance(reflectance), t = luminance(transmittance);
  return r + t > 0.0 ? r / (r + t) : 0.5;
}

Rgb LeafBsdf::eval(const Dir& wo, const Dir& wi) const {
  return (same_hemisphere(wo, wi) ? reflectance : transmittance) / kPi;
}

double LeafBsdf::pdf(const Dir& wo, const Dir& wi) const {
  const double pr = reflect_probability();
  return (same_hemisphere(wo, wi) ? pr : 1.0 - pr) * std::fabs(wi.z) / kPi;
}

BsdfSample LeafBsdf::sample(const Dir& wo, const glm::dvec3& u) const {
  BsdfSample s;
  const double pr = reflect_probability();
  const bool reflect = u.x < pr;
  Dir wi = sample_cosine_hemisphere({u.y, u.z});
  const double side = wo.z >= 0.0 ? 1.0 : -1.0;
  wi.z *= reflect ? side : -side;
  s.wi = wi;
  s.pdf = pdf(wo, wi);
  s.value = eval(wo, wi);
  s.flags = (reflect ? kReflection : kTransmission) | kDiffuse;
  return s;
}

}  // namespace arbor::mat
