// The material layer: what a surface is made of (bark, a leaf, plain diffuse), and how a surface
// point of it becomes a BSDF value. The tracer only finds hits and passes their geometry here.
#pragma once

#include <memory>
#include <variant>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/leaf_bsdf.h"
#include "materials/oren_nayar.h"
#include "materials/textures.h"

namespace arbor::materials {

// What a material needs to know of the surface point it shades (world space, unit vectors).
struct SurfacePoint {
  glm::vec3 shading_normal{0.0f, 0.0f, 1.0f};  // on the side the ray came from
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};                // along the limb, for bark bump mapping
  float along = 0.0f, azimuth = 0.0f, radius = 0.0f;  // bark coordinates (metres, radians, metres)
  glm::vec2 uv{0.0f};                                 // over the unit leaf
  glm::vec3 color{1.0f};   // the primitive's colour, multiplying the albedo
  glm::vec2 ground{0.0f};  // world x, y of a ground point (its patches)
  bool leaf_back = false;  // a leaf seen from its back (the back reflectance applies)
};

// Bark: Oren–Nayar reflection (Lambertian at σ = 0) of an albedo, optionally mapped by an image
// tiled along and round the limb, with bump mapping by procedural furrows or a height image.
struct BarkMaterial {
  glm::vec3 albedo{0.3f};
  float roughness = 0.0f;                // radians (Oren–Nayar σ)
  float bump_height = 0.0f;              // metres of relief
  const HeightMap* bump_map = nullptr;   // null: procedural bark (bark_noise.h)
  float bump_tile = 0.25f;               // metres per repeat of bump_map and albedo_map
  const ColorMap* albedo_map = nullptr;  // multiplies albedo

  glm::vec3 albedo_at(const SurfacePoint& p) const;
  // The shading normal tilted against the bark's height gradient along and round the limb.
  glm::vec3 bumped_normal(const SurfacePoint& p) const;
  // Bark height in [0, 1] at bark coordinates.
  double height(double along, double azimuth, double radius) const;
};

// A thin leaf: diffuse reflection (front and back differ) and diffuse transmission, both
// multiplied by the leaf's albedo map over its uv and the primitive's colour, under an optional
// glossy cuticle on both faces (untinted: the wax reflects white).
struct LeafMaterial {
  glm::vec3 front{0.1f}, back{0.1f}, transmittance{0.1f};
  const ColorMap* albedo_map = nullptr;
  std::shared_ptr<const CuticleCoat> cuticle;  // null: no coat
  bool tinted = true;  // false: R and T as given (mesh leaves have no uv or colour)

  glm::vec3 tint(const SurfacePoint& p) const;
  // The reflectance of the side that was hit, tinted: the albedo AOV of a leaf.
  glm::vec3 reflectance(const SurfacePoint& p) const;
};

// A surface's BSDF at one point, in the shading frame of `normal`: opaque diffuse (bark, ground,
// meshes) or a two-sided leaf.
// The BSDF at a surface point: one of a closed set (Oren–Nayar reflection, the two-sided leaf),
// which the integrator knows only by its lobe flags.
struct SurfaceBsdf {
  std::variant<OrenNayar, LeafBsdf> lobes;
  glm::vec3 normal{0.0f};  // shading normal, on the side the ray came from
  glm::vec3 albedo{0.0f};  // what the albedo AOV shows

  unsigned flags() const {
    if (const LeafBsdf* l = std::get_if<LeafBsdf>(&lobes)) {
      return kReflection | kTransmission | kDiffuse | (l->coat ? kGlossy : 0u);
    }
    return kReflection | kDiffuse;
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
    if (const LeafBsdf* l = std::get_if<LeafBsdf>(&lobes)) {
      return l->sample(wo, glm::dvec3(u_lobe, u.x, u.y));
    }
    return std::get<OrenNayar>(lobes).sample(wo, glm::dvec2(u.x, u.y));
  }
};

// The ground: Lambertian, its albedo mixed with a second one in soft-edged patches where smooth
// 2D noise of the position exceeds the threshold that leaves `cover` of the plane patched.
struct GroundMaterial {
  glm::vec3 patch_albedo{0.0f};
  float scale = 3.0f;                  // metres
  float cover = 0.0f;                  // fraction of the ground patched; set by set_cover
  double threshold = 1e9, edge = 0.1;  // of the noise, from the cover

  // Finds the noise's threshold that leaves `cover` of the plane patched (its quantile over a
  // fixed 512 × 512 sample of the noise, so the same for every scene), and the edges' width.
  void set_cover(float cover);
  // The patch's weight in [0, 1] at world (x, y).
  float patch(glm::vec2 xy) const;
  static double noise(double x, double y);  // the patches' noise, at coordinates in `scale`s
};

// What one surface of a scene is made of.
struct Material {
  enum class Kind { Diffuse, Bark, Leaf, Ground } kind = Kind::Diffuse;
  glm::vec3 albedo{0.5f};  // Diffuse, Ground
  GroundMaterial ground;   // Ground
  BarkMaterial bark;       // Bark
  LeafMaterial leaf;       // Leaf

  // The BSDF at p (normals already facing the incoming ray). The shading normal is kept on the
  // geometric normal's side after bump mapping.
  SurfaceBsdf bsdf(const SurfacePoint& p) const;
  // The albedo AOV at p: bsdf(p).albedo without building the BSDF.
  glm::vec3 albedo_at(const SurfacePoint& p) const;
};

}  // namespace arbor::materials
