// A meadow of grass blades (issue 29; docs/rendering.md, "Meadow"): a few distinct square tiles
// of blades, each blade one normal-oriented cubic Bézier ribbon, repeated over the meadow's area
// by instances — each cell of the tile grid takes one of the tiles, turned by a multiple of 90°,
// chosen by a hash of the cell. So 10⁷ placed blades cost the memory of tiles × density × tile²
// blades. Deterministic: a function of the [meadow] table (its seed) and the animation's clock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "formats/scene_desc.h"
#include "materials/material.h"

namespace arbor::scene {

// One tile's blades, in the tile's own space: x and y in [0, tile), the ground at z = 0.
struct GrassTile {
  static constexpr int kPointsPerBlade = 4;  // one cubic Bézier segment
  std::vector<glm::vec4> points;             // 4 per blade: position and radius (half width)
  std::vector<glm::vec3> normals;            // 4 per blade: the ribbon's upper face
  std::vector<glm::vec3> colors;             // 1 per blade: its tint (dry blades straw)

  std::size_t blades() const { return colors.size(); }
  std::size_t bytes() const {
    return points.size() * sizeof(glm::vec4) + normals.size() * sizeof(glm::vec3) +
           colors.size() * sizeof(glm::vec3);
  }
};

// One cell of the meadow: which tile, where.
struct GrassPlacement {
  int tile = 0;
  glm::mat4 to_world{1.0f}, to_object{1.0f};  // a translation and a turn about z
};

struct Meadow {
  std::vector<GrassTile> tiles;
  std::vector<GrassPlacement> placements;
  materials::Material grass;  // a thin leaf: two-sided, translucent, no cuticle
  std::uint32_t object_id = 0, front_id = 0, back_id = 0;

  bool empty() const { return placements.empty(); }
  std::size_t placed_blades() const;    // over every placement
  std::size_t distinct_blades() const;  // over the tiles
  std::size_t bytes() const;            // the tiles' arrays (not Embree's)
};

// The meadow of `d` at `clock` seconds into the animation (the wind's sway). Empty when the
// density is 0. The material's compositing ids are left for the caller.
Meadow grow_meadow(const formats::MeadowDesc& d, double clock);

// The tile's blades alone (for tests): tile k of the meadow.
GrassTile grow_grass_tile(const formats::MeadowDesc& d, int k, double clock);

}  // namespace arbor::scene
