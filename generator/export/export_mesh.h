// Mesh export of a tessellated tree: Wavefront OBJ (with its .mtl) and binary PLY.
#pragma once

#include <string>

#include "generator/export/text_output.h"
#include "generator/geometry/tree_mesh.h"
#include "generator/species.h"

namespace arbor::generator {

// What the exported materials are: the species' name, bark and leaves.
struct MeshLooks {
  std::string species;
  BarkLook bark;
  LeafLook leaf;
};

// The .mtl written beside an OBJ: the same path with ".mtl" for ".obj".
std::string mtl_path_for(const std::string& obj_path);

// Writes Wavefront OBJ with groups and materials "bark" and "leaf" (`mtllib` naming the .mtl
// beside it, written too), normals and uv. Positions keep 5 decimals (10 µm, a fiftieth of the
// tessellation's smallest chord error), normals and uv 4. Both files atomic, committed together.
void write_obj(const TreeMesh& mesh, const std::string& path, const MeshLooks& looks,
               UpAxis up = UpAxis::Z);
// Writes binary little-endian PLY with normals, uv and a per-face material (0 bark, 1 leaf; the
// header's comments give their colours). Atomic.
void write_ply(const TreeMesh& mesh, const std::string& path, const MeshLooks& looks,
               UpAxis up = UpAxis::Z);

}  // namespace arbor::generator
