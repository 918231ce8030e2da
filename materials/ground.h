// The ground: Lambertian, its albedo mixed with a second one in soft-edged patches where smooth
// 2D noise of the position exceeds the threshold that leaves `cover` of the plane patched; and,
// when asked (issue 29), detail at finer scales — brightness at a quarter, a thirteenth and a
// fiftieth of the patches' scale and drier grass at a third —, small stones on the soil and
// patches of leaf litter over both.
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
  float detail = 0.0f;                 // [0, 1]: the finer scales' strength
  float stones = 0.0f;                 // per m² of soil
  glm::vec3 stone_albedo{0.32f, 0.31f, 0.29f};
  float litter = 0.0f;  // fraction of the ground under leaf litter; set by set_litter
  glm::vec3 litter_albedo{0.20f, 0.13f, 0.07f};
  double litter_threshold = 1e9, litter_edge = 0.1;
  // On a terrain (docs/landscape.md): bare soil and rock over the above where SurfacePoint::
  // terrain says (soil, rock); the rock's albedo varied at two scales and patched with lichen.
  bool terrain = false;
  glm::vec3 soil_albedo{0.19f, 0.15f, 0.11f};
  glm::vec3 rock_albedo{0.30f, 0.29f, 0.26f};

  SurfaceBsdf bsdf(const SurfacePoint& p) const {
    return SurfaceBsdf::diffuse(p.shading_normal, albedo_at(p));
  }
  glm::vec3 albedo_at(const SurfacePoint& p) const;
  // Finds the noise's threshold that leaves `cover` of the plane patched (its quantile over a
  // fixed 512 × 512 sample of the noise, so the same for every scene), and the edges' width.
  void set_cover(float cover);
  void set_litter(float cover);  // the same for the litter's patches
  // The threshold of the noise that leaves `cover` above it, and the edges' width.
  static void quantiles(float cover, double& threshold, double& edge);
  float litter_weight(glm::vec2 xy) const;
  glm::vec3 detailed(glm::vec3 soil, glm::vec3 grass, float w, glm::vec2 xy) const;
  // The rock's albedo at world (x, y): lichen-spotted, varied at 2 m and 30 cm.
  glm::vec3 rock_at(glm::vec2 xy) const;
  // The patch's weight in [0, 1] at world (x, y).
  float patch(glm::vec2 xy) const;
  static double noise(double x, double y);  // the patches' noise, at coordinates in `scale`s
};

}  // namespace arbor::materials
