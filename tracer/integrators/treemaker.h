// The approximate integrator: TREE-MAKER's shading (Neighbors & Hodges 1990, §III, Figure 3)
// at the first visible surface, and its ground shadow. No light transport: one closest hit per
// camera sample, one shadow ray for ground and mesh points.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "materials/treemaker_weights.h"
#include "imaging/color.h"
#include "imaging/treemaker_channels.h"
#include "tracer/integrators/path.h"
#include "tracer/sampler.h"
#include "tracer/lights/sky.h"
#include "tracer/embree/world.h"

namespace arbor::tracer {

// The five factors of Figure 3's shade, in its order: 1, N·L, h/h0, r/r0, sin(q/2).
using TreemakerTerms = std::array<float, 5>;

// The factors at point p of a tree element (§III):
// - N·L: for a leaf triangle (line = false, n its normal) |N·L|, whichever side faces the light —
//   TREE-MAKER shades each element once, before the view is known. For limbs and line elements
//   (line = true, n their tangent T) the normal that lies in the plane of T and L:
//   N·L = sqrt(1 − (T·L)²).
// - h/h0: p's height above the tree's base over the tree's height.
// - r/r0: p's horizontal distance from the vertical trunk axis through the base over r0.
// - sin(q/2): q is the angle at the trunk axis between the horizontal direction to p and the
//   horizontal direction *away* from the light, so sin(q/2) = cos(φ/2) with φ the angle between
//   the directions to p and to the light: 1 on the sun's side of the crown, 0 on the far side.
//   This is the sign that makes a positive angle weight darken "the backside of the tree
//   relative to the sun" as the paper says. On the trunk axis itself, or with the light at the
//   zenith, q is undefined and taken as π/2.
// Heights and distances are not clamped: leaves above the highest skeleton point give h/h0 > 1.
TreemakerTerms treemaker_terms(const scene::TreeExtent& tree, const glm::vec3& p,
                               const glm::vec3& n, bool line, const glm::vec3& to_light);

// Σ weight × factor, the bracket of Figure 3.
float treemaker_shade(const materials::TreemakerWeights& weights, const TreemakerTerms& terms);

// One camera sample of the treemaker integrator. Radiance and colours are scene-linear.
struct TreemakerSample {
  PathSample shade;  // radiance, the first hit's albedo, normal and depth, rays traced
  // AOVs: the factors (0 where no tree is seen); each factor's contribution at weight 1
  // (element colour × MAX_INTENSITY × factor); and the rest of the radiance (sky, ground, meshes).
  // shade.radiance = rest + Σ weight_i × contribution_i.
  TreemakerTerms terms{};
  std::array<glm::vec3, 5> contribution{};
  glm::vec3 rest{0.0f};

  // Writes the "treemaker" AOV channels (treemaker_channel_names() order) to `out`: the factors
  // as they are, the colours exposed and converted like the beauty, so that beauty = tm_rest +
  // Σ weight_i × tm_i holds for the written pixels too.
  void write_aovs(float exposure, const imaging::ColorTransform& to_output, float* out) const;
};

class TreemakerIntegrator {
 public:
  TreemakerIntegrator(const World& world, const Sky& sky);

  TreemakerSample trace(const Ray& camera_ray) const;

  // MAX_INTENSITY of Figure 3 as radiance per unit albedo: (E_sun + E_sky) / π, the radiance of a
  // white Lambertian surface facing the sun under the whole sky. So weights summing to 1 make the
  // brightest element about as bright as the exact renderer's sunlit side.
  glm::vec3 max_intensity() const { return max_intensity_; }
  // Towards the light: the sun, or the zenith when the scene has no sun.
  glm::vec3 light_direction() const { return to_light_; }

 private:
  // Ground and meshes: Lambertian under the sun (when the shadow ray is free) and the whole sky.
  glm::vec3 diffuse_radiance(const WorldHit& hit, std::uint32_t& rays) const;

  const World& world_;
  const Sky& sky_;
  glm::vec3 to_light_{0.0f, 0.0f, 1.0f};
  glm::vec3 sun_irradiance_{0.0f};  // the sun's colour on a plane facing it
  glm::vec3 sky_irradiance_{0.0f};
  glm::vec3 max_intensity_{0.0f};
};

}  // namespace arbor::tracer
