// A plain diffuse material: Lambertian reflection of one albedo (mesh faces with no material of
// their own, mesh "bark", the ground without patches).
#pragma once

#include <glm/vec3.hpp>

#include "materials/surface.h"

namespace arbor::materials {

struct DiffuseMaterial {
  glm::vec3 albedo{0.5f};

  SurfaceBsdf bsdf(const SurfacePoint& p) const {
    return SurfaceBsdf::diffuse(p.shading_normal, albedo);
  }
  glm::vec3 albedo_at(const SurfacePoint&) const { return albedo; }
};

}  // namespace arbor::materials
