// The waxy cuticle of a leaf: a rough dielectric interface over the diffusely scattering
// mesophyll, on both faces of the leaf. Light meeting a face is reflected specularly by the
// cuticle's microfacets (GGX, Walter et al. 2007, with Fresnel) or enters the leaf; the leaf's
// diffuse reflection and transmission act on what entered and leave through the other face's
// (or the same face's) cuticle. The layering is the albedo-scaling approximation: the base lobes
// are scaled by (1 − E(μo)) (1 − E(μi)) / (1 − Ē), where E(μ) is the coat's directional albedo and
// Ē its cosine-weighted mean — symmetric in the two directions (reciprocal) and conserving: a
// leaf with R + T = 1 scatters exactly 1 of what arrives, whatever the coat (docs/rendering.md).
#pragma once

#include <array>
#include <memory>

#include "materials/bsdf.h"

namespace arbor::materials {

class CuticleCoat {
 public:
  // roughness in [0, 1] maps to GGX α = roughness², at least kMinAlpha; ior > 1. The coat's
  // directional albedo is tabulated here (a few milliseconds).
  CuticleCoat(double ior, double roughness);
  // The coat of a leaf material, or null for ior 1 (no coat: the leaf BSDF is the bare diffuse
  // one).
  static std::unique_ptr<const CuticleCoat> make(double ior, double roughness);

  static constexpr double kMinAlpha = 1e-3;  // roughness 0: a mirror to within about 0.1°

  // The roughness a regularised path sees (`[render] regularize`): pbrt-v4's rule on GGX α,
  // α < 0.3 → clamp(2α, 0.1, 0.3), as a roughness (√α); rougher coats are kept.
  static double regularized_roughness(double roughness);

  double ior() const { return ior_; }
  double alpha() const { return alpha_; }

  // The coat's specular reflection f(wo, wi) (no cosine) and the pdf of sample() for it; both
  // directions on the +z side (the caller mirrors a back-face pair to it), else 0.
  double eval(const Dir& wo, const Dir& wi) const;
  double pdf(const Dir& wo, const Dir& wi) const;
  // A reflected direction by sampling the visible normals (Heitz 2018); z ≤ 0 means it failed.
  Dir sample(const Dir& wo, const glm::dvec2& u) const;

  // E(μ): the fraction of light arriving at cos θ = μ that the coat reflects, by linear
  // interpolation of the table; Ē = 2 ∫ E(μ) μ dμ of that same interpolant.
  double albedo(double mu) const;
  double mean_albedo() const { return mean_albedo_; }

  // Unpolarised Fresnel reflectance of a dielectric of index `ior` seen from air at cos θ = c.
  static double fresnel(double c, double ior);

 private:
  static constexpr int kTable = 32;  // μ = k / (kTable − 1)
  double ior_, alpha_;
  std::array<double, kTable> albedo_{};
  double mean_albedo_ = 0.0;
};

}  // namespace arbor::materials
