// The BSDF convention every material follows (stated once, kept everywhere):
// - directions are unit vectors in the local shading frame, z along the shading normal;
// - eval(wo, wi) returns f(wo, wi) WITHOUT the cosine factor (as pbrt);
// - pdf(wo, wi) is a density in solid angle;
// - sample(wo, u) returns value, direction, pdf and lobe flags.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace arbor::materials {

using Rgb = glm::dvec3;
using Dir = glm::dvec3;

// What a BSDF's lobes do: the integrator asks these, never which material made the BSDF.
// kSpecular (a delta lobe: no pdf, never hit by light sampling) is reserved: no lobe has one yet,
// and next-event estimation and regularisation assume so; a lobe that sets it must be handled by
// both (tracer/path.cpp).
enum LobeFlags : unsigned {
  kReflection = 1u,
  kTransmission = 2u,
  kDiffuse = 4u,
  kGlossy = 8u,
  kSpecular = 16u
};

struct BsdfSample {
  Rgb value{0.0};  // f(wo, wi), no cosine
  Dir wi{0.0, 0.0, 1.0};
  double pdf = 0.0;  // solid angle; 0 means the sample failed
  unsigned flags = 0;
};

inline double cos_theta(const Dir& w) { return w.z; }
inline bool same_hemisphere(const Dir& a, const Dir& b) { return a.z * b.z > 0.0; }

// Cosine-weighted direction on the +z hemisphere from two uniform numbers (Malley's method).
Dir sample_cosine_hemisphere(const glm::dvec2& u);

}  // namespace arbor::materials
