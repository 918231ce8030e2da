// One tree's geometry in Embree: a prototype scene (to be placed by instances) with its round
// Hermite curves, displaced trunk grids and leaf triangles; and a closest-hit query.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "generator/geometry/tree_geometry.h"
#include "scene/lod.h"
#include "tracer/embree/embree_device.h"
#include "tracer/ray.h"

struct RTCSceneTy;

namespace arbor::tracer {

// Level of detail (scene/lod.h) for the instances of a prototype: the instances' choices by
// top-level Embree geometry id (the tree instances are geometries 0, 1, … of the world's scene;
// null or past the end: everything, leaves at their own size),
// whether any instance thins its limbs, and how much the leaf cards are enlarged (the largest
// leaf scale of any instance; a hit on a card is mapped back to the instance's own scale).
struct PrototypeLod {
  const std::vector<scene::InstanceLod>* instances = nullptr;
  bool thin_limbs = false;
  float card_scale = 1.0f;
};

class TreePrototype {
 public:
  // Copies the geometry's arrays into Embree buffers and commits the scene (BVH build).
  // `geometry` (and `lod.instances`) must outlive the prototype (hits read its metadata).
  TreePrototype(const EmbreeDevice& device, const generator::TreeGeometry& geometry,
                const PrototypeLod& lod = {});
  ~TreePrototype();
  TreePrototype(const TreePrototype&) = delete;
  TreePrototype& operator=(const TreePrototype&) = delete;

  RTCSceneTy* scene() const { return scene_.get(); }

  // Fills `hit` from Embree's answer for an instanced hit, the ray taken to this prototype's
  // own space (World::intersect carries it back to the world).
  // `leaf_scale`: the instance's (InstanceLod::leaf_scale; 1 without level of detail).
  void describe_hit(const Ray& ray, unsigned geom_id, unsigned primitive, float u, float v, float t,
                    const glm::vec3& embree_ng, SurfaceHit& hit, float leaf_scale = 1.0f) const;

  // What Embree's filters read: the prototype's geometry and its level of detail.
  struct FilterData {
    const generator::TreeGeometry* geometry = nullptr;
    PrototypeLod lod;
  };

 private:
  // The ramiforms' triangles as a geometry of the scene (filtered with the limbs); its id.
  unsigned attach_ramiforms(const EmbreeDevice& device, bool thin_limbs);
  // describe_hit for a ramiform triangle.
  void describe_ramiform(const Ray& ray, unsigned primitive, float u, float v, const glm::vec3& ng,
                         SurfaceHit& hit) const;
  // Normalised height of z in the prototype's bounds (0 bottom, 1 top), for a leaf's variation.
  float crown_height(float z) const {
    const float span = geometry_.bounds_max.z - geometry_.bounds_min.z;
    return span > 0.0f ? (z - geometry_.bounds_min.z) / span : 0.5f;
  }

  const generator::TreeGeometry& geometry_;
  FilterData filter_;
  SceneHandle scene_;
  unsigned curve_id_ = ~0u, grid_id_ = ~0u, leaf_id_ = ~0u, card_id_ = ~0u, ramiform_id_ = ~0u;
};

}  // namespace arbor::tracer
