// The ground: Lambertian, its albedo mixed with a second one in soft-edged patches where smooth
// 2D noise of the position exceeds the threshold that leaves `cover` of the plane patched.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/surface.h"

namespace arbor::materials {

struct GroundMaterial {
  glm::vec3 albedo{0.5f};
  glm::vec3 patch_albedo{0.0f};
  float scale = 3.0f;                  // metres
  float cover = 0.0f;                  // fraction of the ground patched; set by set_cover
  double threshold = 1e9, edge = 0.1;  // of the noise, from the cover

  SurfaceBsdf bsdf(const SurfacePoint& p) const {
    return SurfaceBsdf::diffuse(p.shading_normal, albedo_at(p));
  }
  glm::vec3 albedo_at(const SurfacePoint& p) const;
  // Finds the noise's threshold that leaves `cover` of the plane patched (its quantile over a
  // fixed 512 × 512 sample of the noise, so the same for every scene), and the edges' width.
  void set_cover(float cover);
  // The patch's weight in [0, 1] at world (x, y).
  float patch(glm::vec2 xy) const;
  static double noise(double x, double y);  // the patches' noise, at coordinates in `scale`s
};

}  // namespace arbor::materials
