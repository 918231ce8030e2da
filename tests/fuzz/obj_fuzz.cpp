// Fuzz target: Wavefront OBJ meshes; every index of a read mesh names a vertex.
#include "fuzz_target.h"
#include "formats/obj_mesh.h"

ARBOR_FUZZ_TARGET({
  const arbor::formats::ObjMesh m = arbor::formats::parse_obj(text, "fuzz.obj");
  for (const std::uint32_t i : m.indices)
    arbor::fuzz::require(i < m.positions.size(), "indices name vertices");
  for (const glm::vec3& p : m.positions)
    arbor::fuzz::require(arbor::fuzz::finite(p), "positions are finite");
  arbor::fuzz::require(m.part.size() * 3 == m.indices.size(), "one part per triangle");
})
