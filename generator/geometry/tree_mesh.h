// A tessellated triangle mesh of a tree (limb tubes and leaves), for export to other tools.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "generator/geometry/tree_geometry.h"

namespace arbor::generator {

enum class MeshGroup : std::uint8_t { Bark = 0, Leaf = 1 };

struct TreeMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;  // three per triangle; bark triangles first, then leaves
  std::size_t bark_triangles = 0;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Tessellates the same geometry the renderer uses: each curve segment as a tube whose axial
// resolution comes from Lane's bound (Bloomenthal eq. 4) for a chord error of `tolerance` ×
// radius (at least 0.5 mm) and whose circumferential resolution follows the radius; displaced
// trunk grids and ramiform collars as they are; leaves as their triangles.
// Bark uv: u = fraction of the way round, v = arc length along the limb in metres.
TreeMesh tessellate(const TreeGeometry& geometry, double tolerance = 0.05);

// Lane's bound: segments needed so that chords of a cubic with second-derivative sum `S`
// (Σ over axes of max |x''(u)|, u in [0, 1]) deviate at most `error`: S / (8 n²) ≤ error.
int lane_subdivisions(double second_derivative_sum, double error);

}  // namespace arbor::generator
