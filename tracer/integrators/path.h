// The exact integrator: unidirectional path tracing with next-event estimation to the sun and
// the sky, multiple importance sampling (power heuristic) and Russian roulette.
#pragma once

#include <algorithm>

#include <cstdint>

#include <glm/vec3.hpp>

#include "tracer/sampler.h"
#include "tracer/lights/sky.h"
#include "tracer/embree/world.h"

namespace arbor::tracer {

// What one camera sample brings back: radiance and the first hit's AOVs.
struct PathSample {
  glm::vec3 radiance{0.0f};
  glm::vec3 albedo{0.0f};
  glm::vec3 normal{0.0f};
  float depth = 0.0f;  // distance along the camera ray to the first hit (0 when none)
  bool hit = false;    // the camera ray hit something (alpha)
  std::uint32_t object_id = 0, material_id = 0;  // of the first hit (0: none)
  std::uint32_t rays = 0;                        // rays traced for it (closest-hit and shadow)
};

class PathIntegrator {
 public:
  // `regularize`: after a non-specular bounce, glossy lobes take their regularised roughness
  // (materials::SurfacePoint::regularize; biased, off for references).
  PathIntegrator(const World& world, const Sky& sky, int max_depth, bool regularize = false)
      : world_(world),
        sky_(sky),
        max_depth_(max_depth),
        regularize_(regularize),
        choice_(light_choice(sky)) {}

  // Next-event estimation picks one light per vertex: the sun with probability `sun`, the sky
  // with `sky` (sun + sky is 1, or 0 when neither is worth a shadow ray).
  struct LightChoice {
    float sun = 0.0f, sky = 0.0f;
  };
  // The sky is light-sampled only when its cosine_variance_up() V exceeds S / K + kSkyNeeMargin
  // (S: the sun's irradiance on a level plane, K: the sky's); otherwise BSDF sampling alone finds
  // it, as Cycles does with a constant world, and the sun takes every shadow ray. A sampled sky
  // shares them with the sun by irradiance: the sun's share is its irradiance facing it over that
  // plus K, within [0.1, 0.9].
  static LightChoice light_choice(const Sky& sky);
  static constexpr float kSkyNeeMargin = 0.5f;

  // Dimension pairs 0 and 1 are the camera's (film, lens); each bounce uses four more.
  PathSample trace(const Ray& camera_ray, const PixelSampler& sampler, std::uint32_t index) const;

 private:
  const World& world_;
  const Sky& sky_;
  int max_depth_;
  bool regularize_;
  LightChoice choice_;
};

// The diffuse colour at a hit, scene-linear, as the path integrator shades it: the bark albedo
// with its map and the primitive's colour, the reflectance of the leaf side that was hit (with
// its map and colour), a mesh material's or the ground's albedo. The albedo AOV is this.
glm::vec3 surface_albedo(const WorldHit& hit);

// How far a new ray starts from a surface along its geometric normal (metres): 2e-5 + 4e-6 × the
// largest coordinate — above Embree's float rounding of hit points (including its iterative
// round-curve intersection) at that distance from the origin, and far below twig radii (≥ 1 mm).
float ray_offset(const glm::vec3& p);

// A ray leaving surface point p in direction dir: started ray_offset(p) off the surface on the
// side dir goes to (so transmission through a leaf starts behind it).
Ray spawn_ray(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& dir);

}  // namespace arbor::tracer
