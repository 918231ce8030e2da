// Leaf BSDF: f = R/π in the hemisphere of wo, T/π in the other; lobes chosen by luminance. With a
// cuticle: f = f_coat + (1 − E(μo)) (1 − E(μi)) / (1 − Ē) × (R or T)/π (cuticle.h), the coat on
// whichever face wo is on for reflection.
#include "materials/leaf_bsdf.h"

#include <cmath>
#include "common/math.h"

namespace arbor::materials {

namespace {
double luminance(const Rgb& c) { return arbor::luminance(c.x, c.y, c.z); }

// The pair mirrored so that wo is on +z (a leaf is the same seen from either face).
struct Upper {
  Dir o, i;
  Upper(const Dir& wo, const Dir& wi) : o(wo), i(wi) {
    if (wo.z < 0.0) {
      o.z = -o.z;
      i.z = -i.z;
    }
  }
};

// The base lobes' scale under the coat: what enters at wo and leaves at wi.
double base_scale(const CuticleCoat& c, double mu_o, double mu_i) {
  return (1.0 - c.albedo(mu_o)) * (1.0 - c.albedo(mu_i)) / (1.0 - c.mean_albedo());
}
}  // namespace

double LeafBsdf::reflect_probability() const {
  const double r = luminance(reflectance), t = luminance(transmittance);
  return r + t > 0.0 ? r / (r + t) : 0.5;
}

double LeafBsdf::coat_probability(const Dir& wo) const {
  if (!coat) return 0.0;
  // The coat's share of the leaf's directional albedo E + (1 − E) lum(R + T), at least 0.1 so
  // that glossy highlights on a dark leaf are still found by the BSDF's own samples.
  const double e = coat->albedo(std::fabs(wo.z));
  const double base = (1.0 - e) * luminance(reflectance + transmittance);
  return e + base > 0.0 ? std::max(0.1, e / (e + base)) : 1.0;
}

Rgb LeafBsdf::eval(const Dir& wo, const Dir& wi) const {
  const Rgb diffuse = (same_hemisphere(wo, wi) ? reflectance : transmittance) / kPi;
  if (!coat) return diffuse;
  const Upper up(wo, wi);
  const double scale = base_scale(*coat, up.o.z, std::fabs(up.i.z));
  return diffuse * scale + Rgb(coat->eval(up.o, up.i));
}

double LeafBsdf::pdf(const Dir& wo, const Dir& wi) const {
  const double pr = reflect_probability();
  const double diffuse = (same_hemisphere(wo, wi) ? pr : 1.0 - pr) * std::fabs(wi.z) / kPi;
  if (!coat) return diffuse;
  const double pc = coat_probability(wo);
  const Upper up(wo, wi);
  return (1.0 - pc) * diffuse + pc * coat->pdf(up.o, up.i);
}

BsdfSample LeafBsdf::sample(const Dir& wo, const glm::dvec3& u) const {
  BsdfSample s;
  const double side = wo.z >= 0.0 ? 1.0 : -1.0;
  double u_lobe = u.x;
  const double pc = coat_probability(wo);
  if (pc > 0.0) {
    if (u_lobe < pc) {
      Dir wi = coat->sample(Dir(wo.x, wo.y, side * wo.z), {u.y, u.z});
      if (wi.z <= 0.0) return s;  // below the coat's face: the sample failed
      wi.z *= side;
      s.wi = wi;
      s.pdf = pdf(wo, wi);
      s.value = eval(wo, wi);
      s.flags = kReflection;
      return s;
    }
    u_lobe = (u_lobe - pc) / (1.0 - pc);  // reuse the lobe number for the diffuse lobes
  }
  const double pr = reflect_probability();
  const bool reflect = u_lobe < pr;
  Dir wi = sample_cosine_hemisphere({u.y, u.z});
  wi.z *= reflect ? side : -side;
  s.wi = wi;
  s.pdf = pdf(wo, wi);
  s.value = eval(wo, wi);
  s.flags = (reflect ? kReflection : kTransmission) | kDiffuse;
  return s;
}

}  // namespace arbor::materials
