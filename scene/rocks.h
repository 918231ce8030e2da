// Rocks (docs/landscape.md, "Rocks"): a few boulder shapes — an icosphere displaced by 3D noise,
// squashed, cut by a few planes — placed by instances over an area, on rock and the scree below
// it most, none on slopes steeper than 45° (they would not rest there), with diameters from a
// truncated power law, each lying on the slope (its axis the ground's normal) and sunk along it
// so that its lowest point under its whole footprint is below the surface (no rock floats).
// Deterministic: a function of the [rocks] table and the terrain.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "spec/scene_desc.h"
#include "materials/material.h"
#include "scene/terrain.h"

namespace arbor::scene {

// One shape in its own space: about a unit sphere's size (radius ≤ 1.5), its base at z = bottom.
struct RockShape {
  std::vector<glm::vec3> positions, normals;  // per vertex; smooth normals
  std::vector<std::uint32_t> indices;         // three per triangle, counter-clockwise outward
  float bottom = -1.0f, top = 1.0f;           // the lowest and highest z
  float reach = 1.0f;                         // the largest horizontal distance from the axis
  std::size_t bytes() const {
    return (positions.size() + normals.size()) * sizeof(glm::vec3) +
           indices.size() * sizeof(std::uint32_t);
  }
};

// One placed rock.
struct RockPlacement {
  int shape = 0;
  glm::mat4 to_world{1.0f}, to_object{1.0f};  // a translation, a turn about z, a uniform scale
  float diameter = 0.0f;                      // metres: the shape's scale × 2
  float ground = 0.0f;                        // the terrain's height under its centre
};

struct Rocks {
  std::vector<RockShape> shapes;
  std::vector<RockPlacement> placements;
  materials::Material material;  // the terrain's rock: lichen-spotted, seen in 3D
  std::uint32_t object_id = 0, material_id = 0;

  bool empty() const { return placements.empty(); }
  std::size_t bytes() const;  // the shapes' arrays and the placements
};

// The rocks of `d` on `terrain` (flat ground when it is empty), with their material; the
// compositing ids are left for the caller. InputError at the table when they would be more than
// 10⁷.
Rocks place_rocks(const spec::RocksDesc& d, const Terrain& terrain);

// The share of [rocks] density where the ground's cover is (soil, rock): all on rock, half on the
// soil below it (scree), a twentieth elsewhere (erratics in the meadow); all on flat ground
// without a terrain.
double rock_share(glm::vec2 cover);

// A diameter from the truncated power law p(s) ∝ s^-exponent on [lo, hi], at u in [0, 1).
double power_law_size(double lo, double hi, double exponent, double u);

}  // namespace arbor::scene
