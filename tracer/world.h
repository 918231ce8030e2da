// The renderable world of a scene: one Embree prototype per distinct tree (species, seed, time),
// placed by instances for every [[tree]] and [[forest]] member, and the ground plane. Immutable
// while rendering.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "generator/species.h"
#include "generator/tree_geometry.h"
#include "materials/textures.h"
#include "tracer/embree_scene.h"
#include "tracer/scene_desc.h"

namespace arbor {
class Progress;
}

namespace arbor::trace {

// The looks of one placed tree (species defaults with the scene's overrides).
struct TreeLook {
  glm::vec3 bark_albedo{0.3f};
  float bark_roughness = 0.0f;  // radians (Oren–Nayar σ)
  float bump_height = 0.0f;  // metres
  const mat::HeightMap* bump_map = nullptr;  // null: procedural bark
  float bump_tile = 0.25f;   // metres per repeat of bump_map and bark_albedo_map
  const mat::ColorMap* bark_albedo_map = nullptr;  // multiplies bark_albedo
  const mat::ColorMap* leaf_albedo_map = nullptr;  // over leaf uv, multiplies R and T
  glm::vec3 leaf_front{0.1f}, leaf_back{0.1f}, leaf_transmittance{0.1f};
  gen::TmLight treemaker;  // the TREE-MAKER shading weights (§III) of this tree
};

// A placed tree's extent as TREE-MAKER's shading measures it (§III), in world space: the first
// particle's position (the base of the trunk), the height h0 of the highest skeleton point above
// it and the radius r0, the largest horizontal distance of any skeleton point from it.
struct TreeExtent {
  glm::vec3 base{0.0f};
  float height = 1.0f;
  float radius = 1.0f;
};

// A material of an external mesh, by kind.
struct MeshLook {
  enum class Kind { Bark, Leaf, Diffuse } kind = Kind::Diffuse;
  glm::vec3 albedo{0.5f};
  glm::vec3 leaf_front{0.1f}, leaf_back{0.1f}, leaf_transmittance{0.1f};
};

struct WorldHit {
  SurfaceHit surface;      // in world space
  int instance = -1;       // tree instance; -1 for the ground or a mesh
  bool ground = false;
  const MeshLook* mesh = nullptr;  // set for hits on [[mesh]] geometry
  bool mesh_front = true;          // the side a mesh face's counter-clockwise normal faces
};

struct WorldStats {
  std::size_t prototypes = 0, instances = 0;
  std::size_t curve_segments = 0, triangles = 0;  // over prototypes (not multiplied by instances)
  std::size_t geometry_bytes = 0;
  double build_seconds = 0.0;
};

class World {
 public:
  // ocio_config: the config albedo textures are converted with (arbor's own unless $OCIO).
  World(const SceneDesc& scene, const EmbreeDevice& device, Progress* progress = nullptr);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  bool intersect(const Ray& ray, WorldHit& hit) const;
  // True when anything lies on the ray between t_min and t_max.
  bool occluded(const Ray& ray) const;

  const TreeLook& look(int instance) const { return instances_[static_cast<size_t>(instance)].look; }
  const TreeExtent& extent(int instance) const { return instances_[static_cast<size_t>(instance)].extent; }
  std::size_t instance_count() const { return instances_.size(); }
  const glm::vec3& ground_albedo() const { return ground_albedo_; }
  const WorldStats& stats() const { return stats_; }
  RTCSceneTy* embree_scene() const { return scene_.get(); }  // for benchmarks of raw Embree throughput

 private:
  struct Prototype {
    std::unique_ptr<gen::TreeGeometry> geometry;
    std::unique_ptr<TreePrototype> embree;
    TreeExtent extent;  // in the prototype's own space
  };
  struct Instance {
    int prototype = 0;
    glm::mat4 to_world{1.0f}, to_object{1.0f};
    glm::mat3 normal_to_world{1.0f};
    TreeLook look;
    TreeExtent extent;  // world space
  };
  int prototype_for(const std::string& species_path, std::uint64_t seed, double time,
                    const SourceLocation& where);
  const gen::Species& species(const std::string& path, const SourceLocation& where);
  void add_instance(int prototype, const Placement& placement, const TreeLook& look);
  void add_mesh(const MeshDesc& mesh);
  TreeLook look_for(const gen::Species& species, const BarkOverride& bark,
                    const LeafOverride& leaf, const TreemakerOverride& treemaker,
                    const SourceLocation& where);

  const EmbreeDevice& device_;
  SceneHandle scene_;
  unsigned ground_id_ = ~0u;
  glm::vec3 ground_albedo_{0.0f};
  std::vector<std::pair<std::string, std::unique_ptr<gen::Species>>> species_;
  std::vector<std::pair<std::string, int>> prototype_keys_;
  std::vector<Prototype> prototypes_;
  std::vector<Instance> instances_;
  std::vector<int> instance_of_geometry_;  // Embree geometry id in the top scene → instance
  struct Mesh {
    std::vector<glm::vec3> positions;     // world space
    std::vector<std::uint32_t> indices;   // three per triangle
    std::vector<std::uint16_t> material;  // per triangle, into looks
    std::vector<MeshLook> looks;
  };
  std::vector<Mesh> meshes_;
  std::vector<std::pair<std::string, std::unique_ptr<mat::HeightMap>>> bump_maps_;
  std::vector<std::pair<std::string, std::unique_ptr<mat::ColorMap>>> albedo_maps_;
  const mat::ColorMap* albedo_map(const std::string& path);
  std::string ocio_config_;
  std::vector<int> mesh_of_geometry_;     // Embree geometry id in the top scene → mesh
  WorldStats stats_;
};

}  // namespace arbor::trace
