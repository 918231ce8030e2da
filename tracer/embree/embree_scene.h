// One tree's geometry in Embree: a prototype scene (to be placed by instances) with its round
// Hermite curves, displaced trunk grids and leaf triangles; and a closest-hit query.
#pragma once

#include <glm/vec3.hpp>

#include "generator/geometry/tree_geometry.h"
#include "tracer/embree/embree_device.h"
#include "tracer/ray.h"

struct RTCSceneTy;

namespace arbor::tracer {

class TreePrototype {
 public:
  // Copies the geometry's arrays into Embree buffers and commits the scene (BVH build).
  // `geometry` must outlive the prototype (hits read its metadata).
  TreePrototype(const EmbreeDevice& device, const generator::TreeGeometry& geometry);
  ~TreePrototype();
  TreePrototype(const TreePrototype&) = delete;
  TreePrototype& operator=(const TreePrototype&) = delete;

  RTCSceneTy* scene() const { return scene_.get(); }

  // Fills `hit` from Embree's answer for an instanced hit, the ray taken to this prototype's
  // own space (World::intersect carries it back to the world).
  void describe_hit(const Ray& ray, unsigned geom_id, unsigned primitive, float u, float v, float t,
                    const glm::vec3& embree_ng, SurfaceHit& hit) const;

 private:
  // Normalised height of z in the prototype's bounds (0 bottom, 1 top), for a leaf's variation.
  float crown_height(float z) const {
    const float span = geometry_.bounds_max.z - geometry_.bounds_min.z;
    return span > 0.0f ? (z - geometry_.bounds_min.z) / span : 0.5f;
  }

  const generator::TreeGeometry& geometry_;
  SceneHandle scene_;
  unsigned curve_id_ = ~0u, grid_id_ = ~0u, leaf_id_ = ~0u, card_id_ = ~0u;
};

}  // namespace arbor::tracer
