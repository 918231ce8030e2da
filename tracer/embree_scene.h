// One tree's geometry in Embree: a prototype scene (to be placed by instances) with its round
// Hermite curves, displaced trunk grids and leaf triangles; and a closest-hit query.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "generator/tree_geometry.h"
#include "tracer/embree_device.h"

struct RTCSceneTy;

namespace arbor::trace {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
};

enum class SurfaceKind { None, Curve, Grid, Leaf };

struct SurfaceHit {
  SurfaceKind kind = SurfaceKind::None;
  float t = 0.0f;
  std::uint32_t primitive = 0;
  float u = 0.0f, v = 0.0f;
  glm::vec3 position{0.0f};
  glm::vec3 geometric_normal{0.0f};  // unit, facing the side the ray came from for leaves
  glm::vec3 shading_normal{0.0f};    // unit; follows the displaced surface on trunk grids
  std::uint16_t material = 0;        // gen::MaterialId (leaf front or back by the side hit)
  gen::BarkCoordinates bark;         // for curves and grids
  glm::vec3 tangent{0.0f};           // along the limb (curves and grids), for bump mapping
  std::int32_t leaf = -1;            // Skeleton leaf index for leaf hits
  glm::vec2 uv{0.0f};                // over the unit leaf, for leaf hits
  glm::vec3 color{1.0f};             // the primitive's colour (multiplies its material's albedo)
};

class TreePrototype {
 public:
  // Copies the geometry's arrays into Embree buffers and commits the scene (BVH build).
  // `geometry` must outlive the prototype (hits read its metadata).
  TreePrototype(const EmbreeDevice& device, const gen::TreeGeometry& geometry);
  ~TreePrototype();
  TreePrototype(const TreePrototype&) = delete;
  TreePrototype& operator=(const TreePrototype&) = delete;

  RTCSceneTy* scene() const { return scene_.get(); }
  const gen::TreeGeometry& geometry() const { return geometry_; }
  double build_seconds() const { return build_seconds_; }

  // Closest hit along the ray; false when nothing is hit.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;

  // Fills `hit` from Embree's answer for a ray in this prototype's own space (also used for
  // instanced hits, with the ray taken to object space).
  void describe_hit(const Ray& ray, unsigned geom_id, unsigned primitive, float u, float v,
                    float t, const glm::vec3& embree_ng, SurfaceHit& hit) const;

 private:
  const gen::TreeGeometry& geometry_;
  SceneHandle scene_;
  unsigned curve_id_ = ~0u, grid_id_ = ~0u, leaf_id_ = ~0u;
  double build_seconds_ = 0.0;
};

}  // namespace arbor::trace
