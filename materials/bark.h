// Bark: Oren–Nayar reflection (Lambertian at σ = 0) of an albedo, optionally mapped by an image
// tiled along and round the limb, with bump mapping by procedural furrows or a height image.
#pragma once

#include <glm/vec3.hpp>

#include "materials/bark_color.h"
#include "materials/surface.h"
#include "materials/textures.h"

namespace arbor::materials {

struct BarkMaterial {
  glm::vec3 albedo{0.3f};
  float roughness = 0.0f;                // radians (Oren–Nayar σ)
  float bump_height = 0.0f;              // metres of relief
  const HeightMap* bump_map = nullptr;   // null: procedural bark (bark_noise.h)
  float bump_tile = 0.25f;               // metres per repeat of bump_map and albedo_map
  const ColorMap* albedo_map = nullptr;  // multiplies albedo (and then the pattern is not used)
  BarkPattern pattern;                   // colour by relief and marks (bark_color.h)

  SurfaceBsdf bsdf(const SurfacePoint& p) const;
  glm::vec3 albedo_at(const SurfacePoint& p) const;
  // The shading normal tilted against the bark's height gradient along and round the limb.
  glm::vec3 bumped_normal(const SurfacePoint& p) const;
  // Bark height in [0, 1] at bark coordinates.
  double height(double along, double azimuth, double radius) const;
};

}  // namespace arbor::materials
