// The renderable world: a scene (scene/) in Embree — one prototype scene per grown tree and per
// meadow tile, placed by instances, the meshes and a ground quad — and the hits it answers in world
// space. Immutable while rendering.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/ray.h"

namespace arbor::tracer {

class TreePrototype;
struct PrototypeLod;
class GrassPrototype;

// The rays a render asked the world to trace, in the order they were asked (with several threads
// the order between threads is the scheduler's): for replaying exactly them through Embree alone
// (bench/render_bench.cpp ray_replay), to tell Embree's share of a render's time from arbor's.
struct RayLog {
  std::mutex mutex;
  std::vector<Ray> closest, shadow;
};

class World {
 public:
  // `scene` must outlive the world.
  World(const scene::Scene& scene, const EmbreeDevice& device);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // The closest hit, in world space, with its material; false when the ray escapes.
  bool intersect(const Ray& ray, WorldHit& hit) const;
  // True when anything lies on the ray between t_min and t_max.
  bool occluded(const Ray& ray) const;

  const scene::Scene& scene() const { return scene_; }
  const scene::TreeInstance& instance(int i) const {
    return scene_.instances[static_cast<std::size_t>(i)];
  }
  const scene::TreeExtent& extent(int i) const { return instance(i).extent; }
  // Instance i's level of detail as rendered (its leaf scale calibrated; scene/lod.h).
  const scene::InstanceLod& lod(int i) const { return lod_[static_cast<std::size_t>(i)]; }
  double build_seconds() const { return build_seconds_; }  // the BVHs, after the scene
  RTCSceneTy* embree_scene() const {
    return top_.get();
  }  // for benchmarks of raw Embree throughput
  // Records every ray traced from now on into `log` (null: stop); for benchmarks.
  void log_rays(RayLog* log) { log_ = log; }

 private:
  // Sets each thinned instance's leaf scale from its prototype's calibrated leaf area.
  void calibrate_leaves(const std::vector<PrototypeLod>& lods);
  // Puts the terrain into Embree: its grid in a compact scene of its own, instanced in the top.
  void attach_terrain(const scene::Terrain& terrain);
  // Fills `hit` for a hit on the terrain.
  void describe_terrain(const Ray& ray, float t, glm::vec3 ng, bool skirt, WorldHit& hit) const;
  // The distance along `ray` to the ground plane beyond its quad (within the ray's extent), or
  // −1: for a ray Embree found no hit for.
  float plane_beyond(const Ray& ray) const;
  // Fills `hit` for a hit on the ground plane at `t`.
  void describe_plane(const Ray& ray, float t, WorldHit& hit) const;
  // The ground plane's height on a terrain: a millimetre under its lowest level.
  float ground_level() const { return static_cast<float>(scene_.terrain.floor()) - 1e-3f; }
  static constexpr unsigned kSkirtGeometry = 2;  // in the terrain's scene: square, surround, skirt
  // Puts the rocks into Embree: each shape a scene of its own, each rock an instance of it.
  void attach_rocks(const scene::Rocks& rocks);
  // Fills `hit` for a hit on triangle `primitive` of rock `rock` (world-space ray).
  void describe_rock(const Ray& ray, unsigned primitive, float u, float v, float t, int rock,
                     WorldHit& hit) const;
  // Fills `hit` for a hit on `blade` of meadow placement `placement` (world-space ray).
  void describe_grass(const Ray& ray, unsigned blade, float u, float t, int placement,
                      WorldHit& hit) const;

  const scene::Scene& scene_;
  const EmbreeDevice& device_;
  SceneHandle top_;
  std::vector<std::unique_ptr<TreePrototype>> prototypes_;
  std::vector<std::unique_ptr<GrassPrototype>> grass_;  // one per meadow tile
  std::vector<int> grass_of_geometry_;  // Embree geometry id in the top scene → meadow placement
  std::vector<int> instance_of_geometry_;  // Embree geometry id in the top scene → instance
  // The tree instances' level of detail (scene/lod.h), their leaf scales calibrated by the
  // crowns' cover (lod_calibration.h); instance i is geometry i of the top scene.
  std::vector<scene::InstanceLod> lod_;
  std::vector<int> mesh_of_geometry_;
  std::vector<SceneHandle> rock_shapes_;  // one per rock shape
  std::vector<int> rock_of_geometry_;     // Embree geometry id in the top scene → rock
  SceneHandle terrain_;                   // the terrain's own scene (none: null)
  unsigned terrain_geometry_ = ~0u;       // its instance's Embree geometry id in the top scene  //
                                          // Embree geometry id in the top scene → mesh
  double build_seconds_ = 0.0;
  RayLog* log_ = nullptr;
};

}  // namespace arbor::tracer
