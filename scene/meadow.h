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

#include "spec/scene_desc.h"
#include "materials/material.h"
#include "scene/terrain.h"

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
  // A translation and a turn about z; on a terrain also a shear z += a·x + b·y + c that lays the
  // tile's ground on the terrain's triangle (sheared: normals go by the inverse transpose).
  glm::mat4 to_world{1.0f}, to_object{1.0f};
  bool sheared = false;
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
//
// On a terrain (not empty) the tiles are the terrain's cells (d.tile is its spacing) and each
// is cut along the cell's diagonal into its two triangles, so that a shear lays each half
// exactly on the rendered triangle under it: every blade's root is on the surface. A half is
// kept at one of four densities (all its blades, ½, ¼ or ⅛: a prefix of its random order), chosen
// at random so that the mean density of a triangle is d.density × triangle_grass_share().
Meadow grow_meadow(const spec::MeadowDesc& d, double clock, const Terrain& terrain = {});

// The share of a meadow's density that grows where the terrain's cover is (soil, rock): none on
// rock, 30 % on bare soil (scene/ground.h paints them), all elsewhere.
double grass_share(glm::vec2 cover);

// The share of grass on triangle `upper` (0: (v0, v1, v3), 1: (v2, v3, v1)) of terrain cell
// (i, j): the least grass_share at its centroid and at the points ⅔ of the way from there to its
// corners, so that no grass grows on a triangle that is partly rock.
double triangle_grass_share(const Terrain& terrain, int i, int j, int upper);

// The tile's blades alone (for tests): tile k of the meadow.
GrassTile grow_grass_tile(const spec::MeadowDesc& d, int k, double clock);

}  // namespace arbor::scene
