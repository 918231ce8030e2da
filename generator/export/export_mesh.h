// Mesh export of a tessellated tree: Wavefront OBJ and binary PLY.
#pragma once

#include <string>

#include "generator/geometry/tree_mesh.h"

namespace arbor::gen {

// Writes Wavefront OBJ with groups "bark" and "leaf", normals and uv. Atomic.
void write_obj(const TreeMesh& mesh, const std::string& path);
// Writes binary little-endian PLY with normals, uv and a per-face material (0 bark, 1 leaf).
void write_ply(const TreeMesh& mesh, const std::string& path);

}  // namespace arbor::gen
