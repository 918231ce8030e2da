// A landscape's parts in the pbrt-v4 export (docs/rendering.md, "pbrt-v4 export"): the terrain as
// a binary PLY mesh with its albedo baked into an image, the rocks as object instances.
#pragma once

#include <cstddef>
#include <string>

#include <glm/vec3.hpp>

#include "imaging/color.h"
#include "imaging/image_output.h"
#include "materials/ground.h"
#include "scene/rocks.h"
#include "scene/terrain.h"

namespace arbor::tracer {

// The terrain's mesh beside OUT.pbrt: OUT.terrain.ply; its albedo: OUT.terrain.exr.
std::string terrain_mesh_path_for(const std::string& pbrt_path);
std::string terrain_albedo_path_for(const std::string& pbrt_path);
// The surround's: OUT.surround.ply and OUT.surround.exr.
std::string surround_mesh_path_for(const std::string& pbrt_path);
std::string surround_albedo_path_for(const std::string& pbrt_path);

// Writes `t` as a binary little-endian PLY at `path` (atomically): every vertex of its grid with
// its smooth normal and uv = its place in the square, (0, 0) at the corner (x0, y0); each cell
// the two triangles Embree renders, (v0, v1, v3) and (v2, v3, v1).
void write_terrain_ply(const scene::Terrain& t, const std::string& path);

// The texels a side of the terrain's albedo image: half its grid spacing, at most 4096 along the
// longer side, square texels.
struct TerrainTexels {
  int columns = 0, rows = 0;
};
TerrainTexels terrain_texels(const scene::Terrain& t);

// The terrain's albedo (`ground`'s, with its soil and rock by the terrain's cover) over its
// square, the mean of 2 × 2 points in each texel, turned into pbrt's colour space by `to_pbrt`
// (empty: the same space) and clamped to [0, 1] (`clamped` counts the texels that were), laid out
// as pbrt's imagemap reads uv: row 0 at the square's +y edge, column 0 at its −x edge.
imaging::Image terrain_albedo(const scene::Terrain& t, const materials::GroundMaterial& ground,
                              const imaging::ColorTransform& to_pbrt, std::size_t& clamped);

// The rocks' mean albedo (their lichen-spotted rock averaged over 40 m of its pattern), in
// scene-linear.
glm::vec3 mean_rock_albedo(const materials::GroundMaterial& rock);

// The rocks as pbrt text: each shape once, as an object of a `trianglemesh` with its smooth
// normals in `material`, and each placement an ObjectInstance under its Transform.
std::string rocks_text(const scene::Rocks& rocks, const std::string& material);

}  // namespace arbor::tracer
