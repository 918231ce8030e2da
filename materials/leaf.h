// A thin leaf: diffuse reflection (front and back differ) and diffuse transmission, both
// multiplied by the leaf's albedo map over its uv, the primitive's colour and the leaf's own
// variation, under an optional glossy cuticle on both faces (untinted: the wax reflects white).
// Where a tint would make reflectance + transmittance exceed 1 in a channel, both are scaled down
// to sum to 1 there: a leaf never creates energy.
#pragma once

#include <glm/vec3.hpp>

#include "materials/cuticle.h"
#include "materials/leaf_texture.h"
#include "materials/leaf_variation.h"
#include "materials/surface.h"
#include "materials/textures.h"

namespace arbor::materials {

struct LeafMaterial {
  glm::vec3 front{0.1f}, back{0.1f}, transmittance{0.1f};
  const ColorMap* albedo_map = nullptr;
  // The cuticle, owned by the scene like the maps (one coat per ior and roughness, shared by
  // every leaf material that has it); null: no coat.
  const CuticleCoat* cuticle = nullptr;
  // The same coat roughened for regularised paths (`[render] regularize`; pbrt-v4's rule:
  // GGX α < 0.3 becomes clamp(2α, 0.1, 0.3)); null: the cuticle serves them too.
  const CuticleCoat* regularized = nullptr;
  bool tinted = true;       // false: R and T as given (mesh leaves have no uv or colour)
  LeafVariation variation;  // each leaf's own tint (materials/leaf_variation.h); none by default
  LeafSeason season;        // spring's or autumn's tint (materials/leaf_variation.h); summer: none
  LeafTexture texture;      // midrib, veins and margin over the uv (materials/leaf_texture.h)

  SurfaceBsdf bsdf(const SurfacePoint& p) const;
  glm::vec3 tint(const SurfacePoint& p) const;
  // The reflectance of the side that was hit, tinted: the albedo AOV of a leaf.
  glm::vec3 albedo_at(const SurfacePoint& p) const;
};

}  // namespace arbor::materials
