// A scene ready to render, without Embree: every distinct tree grown once (species, seed, time),
// its placements with their materials, the meshes in world space, the ground. Immutable once
// built; the tracer's Embree world is made from it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "spec/scene_desc.h"
#include "generator/geometry/tree_geometry.h"
#include "materials/treemaker_weights.h"
#include "materials/material.h"
#include "scene/community.h"
#include "scene/lod.h"
#include "scene/meadow.h"
#include "scene/rocks.h"
#include "scene/terrain.h"

namespace arbor {
class Progress;
}

namespace arbor::scene {

// A placed tree's extent as TREE-MAKER's shading measures it (§III), in world space: the first
// particle's position (the base of the trunk), the height h0 of the highest skeleton point above
// it and the radius r0, the largest horizontal distance of any skeleton point from it.
struct TreeExtent {
  glm::vec3 base{0.0f};
  float height = 1.0f;
  float radius = 1.0f;
};

// One grown tree, shared by every instance of the same (species, seed, time).
struct TreePrototypeData {
  std::unique_ptr<generator::TreeGeometry> geometry;
  TreeExtent extent;  // in the prototype's own space
};

// One placed tree.
struct TreeInstance {
  int prototype = 0;
  glm::mat4 to_world{1.0f}, to_object{1.0f};
  glm::mat3 normal_to_world{1.0f};
  materials::Material bark, leaf;         // species defaults with the scene's overrides
  materials::TreemakerWeights treemaker;  // the TREE-MAKER shading weights (§III) of this tree
  TreeExtent extent;                      // world space
  InstanceLod lod;  // what it keeps at its range ([render] lod; everything when off)
  // Compositing ids (1-based into Scene::object_names / material_names; docs/outputs.md).
  std::uint32_t object_id = 0;
  std::uint32_t bark_id = 0, leaf_front_id = 0, leaf_back_id = 0;
};

// An external mesh in world space.
struct MeshObject {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle
  // The OBJ's vertex normals, placed in the world (unit length), and three indices into them
  // per triangle (kNoNormal: that corner has none, the triangle is flat); both empty when the
  // file has no `vn`.
  static constexpr std::uint32_t kNoNormal = 0xffffffffu;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> normal_indices;
  std::vector<std::uint16_t> material;  // per triangle, into materials
  std::vector<materials::Material> materials;
  std::uint32_t object_id = 0;              // compositing ids, as for a TreeInstance
  std::vector<std::uint32_t> material_ids;  // per material
};

struct SceneStats {
  std::size_t prototypes = 0, instances = 0;
  std::size_t curve_segments = 0, triangles = 0;  // over prototypes (not multiplied by instances)
  std::size_t geometry_bytes = 0;   // arbor's arrays of trees and meshes (not Embree's BVH)
  double build_seconds = 0.0;       // growing trees and building their geometry, everything
  double simulation_seconds = 0.0;  // of which the community's simulation
};

struct Scene {
  std::vector<TreePrototypeData> prototypes;
  std::vector<TreeInstance> instances;
  std::vector<MeshObject> meshes;
  bool has_ground = false;
  materials::Material ground;
  std::uint32_t ground_object_id = 0, ground_material_id = 0;
  // The community's plants (scene/community.h) in the order of their instances, which follow the
  // trees' and the forests'.
  struct CommunityPlant {
    std::size_t instance = 0;
    int species = 0, variant = 0;
    double age = 0.0, radius = 0.0;
  };
  std::vector<CommunityPlant> community;
  Meadow meadow;    // empty: none
  Terrain terrain;  // empty: none (the ground plane alone)
  Rocks rocks;      // empty: none
  std::uint32_t terrain_object_id = 0;
  // The names of the compositing ids (id k is names[k - 1]; 0 is nothing, the sky): objects are
  // "<species>.<n>" (the n-th tree of that species in scene order), "<mesh file stem>.<n>",
  // "ground", "terrain", "meadow" and "rocks"; materials "<species>/bark", "<species>/leaf front",
  // "<species>/leaf back", "<mesh file stem>/<OBJ material or group>", "ground", "meadow/blade
  // front", "meadow/blade back" and "rocks". Names are unique; one name, one id.
  std::vector<std::string> object_names, material_names;
  SceneStats stats;
  // The textures the materials point to.
  std::vector<std::pair<std::string, std::unique_ptr<materials::HeightMap>>> bump_maps;
  std::vector<std::pair<std::string, std::unique_ptr<materials::ColorMap>>> albedo_maps;
  // The leaves' cuticles, one per (ior, roughness) in use (its albedo table computed once).
  std::vector<std::unique_ptr<const materials::CuticleCoat>> coats;
};

// Builds the scene: loads each species once, grows each tree once, assembles materials (albedo
// maps converted through the OCIO config `ocio_config`), reads the meshes. InputError for bad
// species, meshes or textures, at the scene key that names them. With a `geometry_budget` (bytes;
// 0: none), a forest whose variants would need more is refused once its first variant is grown
// (InputError at the forest): each variant is taken at the first one's size, twice over for
// Embree's structures over it. The trees' prototypes and a forest's variants are grown on up to
// `threads` threads (0: every core); the scene is the same at any thread count.
std::unique_ptr<const Scene> build_scene(const spec::SceneDesc& desc,
                                         const std::string& ocio_config,
                                         Progress* progress = nullptr,
                                         std::uint64_t geometry_budget = 0, unsigned threads = 0);

// The affine map of a placement: translate · rotate about z · uniform scale.
glm::mat4 placement_matrix(const spec::Placement& placement);

}  // namespace arbor::scene
