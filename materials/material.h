// The material layer: what a surface is made of — one of a closed set of kinds (diffuse, bark, a
// leaf, the ground), one file each — and how a surface point of it becomes a BSDF. The tracer
// only finds hits and passes their geometry here.
#pragma once

#include <utility>
#include <variant>

#include <glm/geometric.hpp>

#include "materials/bark.h"
#include "materials/diffuse.h"
#include "materials/ground.h"
#include "materials/leaf.h"
#include "materials/surface.h"

namespace arbor::materials {

struct Material {
  std::variant<DiffuseMaterial, BarkMaterial, LeafMaterial, GroundMaterial> kind;

  Material() = default;
  template <class Kind>
  Material(Kind k) : kind(std::move(k)) {}  // NOLINT: any kind is a material

  // The kind, if this material is one (null otherwise).
  template <class Kind>
  const Kind* as() const {
    return std::get_if<Kind>(&kind);
  }
  // The BSDF at p (normals already facing the incoming ray). The shading normal is kept on the
  // geometric normal's side after bump mapping.
  SurfaceBsdf bsdf(const SurfacePoint& p) const {
    SurfaceBsdf b = std::visit([&](const auto& m) { return m.bsdf(p); }, kind);
    if (glm::dot(b.normal, p.geometric_normal) < 0.0f) b.normal = -b.normal;
    return b;
  }
  // The albedo AOV at p: bsdf(p).albedo without building the BSDF.
  glm::vec3 albedo_at(const SurfacePoint& p) const {
    return std::visit([&](const auto& m) { return m.albedo_at(p); }, kind);
  }
};

}  // namespace arbor::materials
