// Rays and what they hit: the types the camera, the Embree world and the integrators share.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/rng.h"
#include "generator/geometry/tree_geometry.h"
#include "materials/material.h"

namespace arbor::tracer {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
};

enum class SurfaceKind { None, Curve, Grid, Leaf, Ramiform };

// A hit on one tree prototype, in the space of the hit (the prototype's own, or the world's).
struct SurfaceHit {
  SurfaceKind kind = SurfaceKind::None;
  float t = 0.0f;
  std::uint32_t primitive = 0;
  float u = 0.0f, v = 0.0f;
  glm::vec3 position{0.0f};
  glm::vec3 geometric_normal{0.0f};  // unit, facing the side the ray came from for leaves
  glm::vec3 shading_normal{0.0f};    // unit; follows the displaced surface on trunk grids
  std::uint16_t material = 0;        // generator::MaterialId (leaf front or back by the side hit)
  generator::BarkCoordinates bark;   // for curves and grids
  glm::vec3 tangent{0.0f};           // along the limb (curves and grids), for bump mapping
  std::int32_t leaf = -1;            // Skeleton leaf index for leaf hits
  glm::vec2 uv{0.0f};                // over the unit leaf, for leaf hits; a rock's pattern
  glm::vec3 color{1.0f};             // the primitive's colour (multiplies its material's albedo)
  float crown_height = 0.5f;         // leaf hits: height in the prototype's bounds, 0 to 1
  glm::vec2 terrain{0.0f};           // terrain hits: the ground's (soil, rock) cover
};

// A hit in the world: the surface in world space and what it is made of.
struct WorldHit {
  SurfaceHit surface;
  int instance = -1;  // tree instance; -1 for the ground, a mesh or grass
  int grass = -1;     // meadow placement (scene::Meadow::placements) of a blade; -1 otherwise
  bool ground = false;
  bool mesh = false;       // a [[mesh]] face
  bool rock = false;       // a rock's face (its pattern's coordinates in surface.uv)
  bool mesh_front = true;  // the side a mesh face's counter-clockwise normal faces
  const materials::Material* material = nullptr;
  // Compositing ids (Scene::object_names / material_names, 1-based).
  std::uint32_t object_id = 0, material_id = 0;

  // The point as the material layer sees it.
  // `regularize`: the path asks for regularised glossy lobes (tracer/integrators/path.h).
  materials::SurfacePoint point(bool regularize = false) const {
    materials::SurfacePoint p;
    p.regularize = regularize;
    p.shading_normal = surface.shading_normal;
    p.geometric_normal = surface.geometric_normal;
    p.tangent = surface.tangent;
    p.along = surface.bark.along;
    p.azimuth = surface.bark.azimuth;
    p.radius = surface.bark.radius;
    p.uv = surface.uv;
    p.color = surface.color;
    if (ground) p.ground = glm::vec2(surface.position.x, surface.position.y);
    if (rock) p.ground = surface.uv;
    p.terrain = surface.terrain;
    p.height = surface.position.z;
    p.leaf_back = mesh ? !mesh_front : surface.material == generator::kMaterialLeafBack;
    if (surface.leaf >= 0) {
      // Each leaf of each tree its own: trees that share a prototype differ too.
      // A blade's key: its placement's (counted down from 2⁶⁴ − 1, apart from the trees').
      const std::uint64_t owner = grass >= 0 ? ~static_cast<std::uint64_t>(grass)
                                             : static_cast<std::uint64_t>(instance) + 1;
      p.leaf_key = derive_key(owner, static_cast<std::uint64_t>(surface.leaf));
      p.crown_height = surface.crown_height;
    }
    return p;
  }
};

}  // namespace arbor::tracer
