// Wavefront OBJ meshes as plain data: positions, triangles, and each triangle's group and
// material names, every record checked with its line and column.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace arbor::formats {

struct ObjMesh {
  // A run of faces under one group (`g`/`o`) and one material (`usemtl`).
  struct Part {
    std::string group, material;
  };
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle, into positions
  std::vector<glm::vec3> normals;      // the `vn` records, unit length
  // Three per triangle, into normals, when the file has any `vn`: kNoNormal for a corner
  // without one (such a triangle is shaded flat).
  std::vector<std::uint32_t> normal_indices;
  static constexpr std::uint32_t kNoNormal = 0xffffffffu;
  std::vector<std::uint32_t> part;  // per triangle, into parts
  std::vector<Part> parts;
  std::vector<int> part_line;  // per part: the line of its first face
};

// Reads OBJ text. Faces of n ≥ 3 vertices become n − 2 triangles, fanned from the first vertex
// (exact for the convex polygons exporters write). Vertex normals (`vn`, `v//vn`, `v/vt/vn`) are
// kept for smooth shading; texture coordinates are checked but not kept. Throws InputError at
// the record for a number that is not finite, a normal of zero length, an index that is 0, too
// large or names no vertex, a face of fewer than three vertices, an unknown statement.
ObjMesh parse_obj(std::string_view text, const std::string& path);

// Reads an OBJ file; InputError when it cannot be read or is malformed.
ObjMesh load_obj(const std::string& path);

}  // namespace arbor::formats
