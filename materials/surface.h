// What a material sees of a surface point, and the BSDF it makes there: the closed set of lobes
// (Oren–Nayar reflection, the two-sided leaf) that the integrator knows only by their flags.
#pragma once

#include <cstdint>
#include <variant>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/leaf_bsdf.h"
#include "materials/oren_nayar.h"

namespace arbor::materials {

// What a material needs to know of the surface point it shades (world space, unit vectors).
struct SurfacePoint {
  glm::vec3 shading_normal{0.0f, 0.0f, 1.0f};  // on the side the ray came from
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};                // along the limb, for bark bump mapping
  float along = 0.0f, azimuth = 0.0f, radius = 0.0f;  // bark coordinates (metres, radians, metres)
  glm::vec2 uv{0.0f};                                 // over the unit leaf
  glm::vec3 color{1.0f};    // the primitive's colour, multiplying the albedo
  glm::vec2 ground{0.0f};   // world x, y of a ground point (its patches)
  float height = 0.0f;      // world z (m above the ground plane): the bark's base
  glm::vec2 terrain{0.0f};  // a terrain's (soil, rock) cover at a ground point (scene/terrain.h)
  bool leaf_back = false;   // a leaf seen from its back (the back reflectance applies)
  // The path has bounced off a non-specular surface and `[render] regularize` is on: glossy
  // lobes use their regularised roughness (LeafMaterial::regularized).
  bool regularize = false;
  std::uint64_t leaf_key = 0;  // the leaf's own key (tree instance and leaf), for its variation
  float crown_height = 0.5f;   // the leaf's height in its tree's crown, 0 bottom to 1 top
};

// The BSDF at a surface point: one of a closed set (Oren–Nayar reflection, the two-sided leaf),
// which the integrator knows only by its lobe flags.
struct SurfaceBsdf {
  std::variant<OrenNayar, LeafBsdf> lobes;
  glm::vec3 normal{0.0f};  // shading normal, on the side the ray came from
  glm::vec3 albedo{0.0f};  // what the albedo AOV shows

  // An opaque diffuse surface of `albedo` (σ: Oren–Nayar roughness, radians) about `normal`.
  static SurfaceBsdf diffuse(glm::vec3 normal, glm::vec3 albedo, float sigma = 0.0f) {
    SurfaceBsdf b;
    OrenNayar lobe;
    lobe.albedo = glm::dvec3(albedo);
    lobe.sigma = sigma;
    b.lobes = lobe;
    b.normal = normal;
    b.albedo = glm::vec3(lobe.albedo);
    return b;
  }

  // Every lobe answers flags(), eval(), pdf() and sample() with one signature each; a lobe added to
  // the variant without them does not compile.
  unsigned flags() const {
    return std::visit([](const auto& b) { return b.flags(); }, lobes);
  }
  // Light may arrive and leave through the surface (both sides of a leaf).
  bool transmits() const { return (flags() & kTransmission) != 0; }

  glm::vec3 eval(const glm::dvec3& wo, const glm::dvec3& wi) const {
    return glm::vec3(std::visit([&](const auto& b) { return b.eval(wo, wi); }, lobes));
  }
  float pdf(const glm::dvec3& wo, const glm::dvec3& wi) const {
    return static_cast<float>(std::visit([&](const auto& b) { return b.pdf(wo, wi); }, lobes));
  }
  // u chooses the direction, u_lobe the leaf's lobe (reflect or transmit).
  BsdfSample sample(const glm::dvec3& wo, glm::vec2 u, float u_lobe) const {
    const glm::dvec3 v(u_lobe, u.x, u.y);
    return std::visit([&](const auto& b) { return b.sample(wo, v); }, lobes);
  }
};

}  // namespace arbor::materials
