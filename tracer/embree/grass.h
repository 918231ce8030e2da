// A meadow's tile of grass blades in Embree (scene/meadow.h): one prototype scene of
// normal-oriented cubic Bézier ribbons, placed over the meadow by instances; and what a hit on a
// blade is.
#pragma once

#include <glm/vec3.hpp>

#include "scene/meadow.h"
#include "tracer/embree/embree_device.h"
#include "tracer/ray.h"

namespace arbor::tracer {

class GrassPrototype {
 public:
  // Shares the tile's points with Embree, copies its normals; `tile` must outlive the prototype.
  GrassPrototype(const EmbreeDevice& device, const scene::GrassTile& tile);
  ~GrassPrototype();
  GrassPrototype(const GrassPrototype&) = delete;
  GrassPrototype& operator=(const GrassPrototype&) = delete;

  RTCSceneTy* scene() const { return scene_.get(); }

  // Fills `hit` for a hit on blade `blade` at curve parameter u (0 at the root, 1 at the tip),
  // the ray in the tile's space: a leaf hit, its front the blade's upper face; `leaf` is the
  // blade, `crown_height` how far up it the hit is.
  void describe_hit(const Ray& ray, unsigned blade, float u, float t, SurfaceHit& hit) const;

 private:
  const scene::GrassTile& tile_;
  SceneHandle scene_;
};

}  // namespace arbor::tracer
