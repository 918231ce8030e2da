// A tessellated triangle mesh of a tree (limb tubes and leaves), for export to other tools.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "generator/skeleton.h"

namespace arbor::gen {

enum class MeshGroup : std::uint8_t { Bark = 0, Leaf = 1 };

struct TreeMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;  // three per triangle; bark triangles first, then leaves
  std::size_t bark_triangles = 0;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Tessellates every stem as a tube (rings at its points, more where the taper or the trunk's
// flare is not linear, lobes on the trunk's section) and every leaf from its LeafShape.
// Bark uv: u = fraction of the way round, v = arc length / circumference at the stem's base.
TreeMesh tessellate(const Skeleton& skeleton);

// Writes Wavefront OBJ with groups "bark" and "leaf", normals and uv. Atomic.
void write_obj(const TreeMesh& mesh, const std::string& path);
// Writes binary little-endian PLY with normals, uv and a per-face material (0 bark, 1 leaf).
void write_ply(const TreeMesh& mesh, const std::string& path);

}  // namespace arbor::gen
