// Path tracing with NEE + MIS + Russian roulette. The material layer turns each hit into a plain
// BSDF value; nothing is allocated per sample.
#include "tracer/integrators/path.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/frame.h"
#include "tracer/lights/aerial.h"

namespace arbor::tracer {

namespace {

float power_heuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

// Whether next-event estimation takes the sun; the choice's random number is drawn only when
// there are two lights to choose from (with one, u < 1 and u < 0 decide alike without it).
bool picks_sun(const PathIntegrator::LightChoice& c, const PixelSampler& sampler,
               std::uint32_t index, std::uint32_t dim) {
  if (c.sun >= 1.0f) return true;
  if (c.sun <= 0.0f) return false;
  return sampler.get2d(index, dim).x < c.sun;
}

// What the camera ray's hit records (the AOVs), and the air before the surface when the sky has
// aerial perspective: the surface's light dimmed, the air's own light added.
void first_hit(const WorldHit& hit, const materials::SurfaceBsdf& sh, const Ray& ray,
               const Sky& sky, PathSample& out, glm::vec3& beta) {
  out.albedo = sh.albedo;
  out.normal = sh.normal;
  out.depth = hit.surface.t;
  out.hit = true;
  out.object_id = hit.object_id;
  out.material_id = hit.material_id;
  if (const AerialPerspective* air = sky.aerial()) {
    const AerialPerspective::Sample a = air->at(ray.direction, hit.surface.t);
    out.radiance += a.inscattered;
    beta *= a.transmittance;
  }
}

}  // namespace

PathIntegrator::LightChoice PathIntegrator::light_choice(const Sky& sky) {
  const float sun = sky.has_sun() ? sky.sun_irradiance() : 0.0f;
  const glm::vec3 e = sky.irradiance_up();
  const float k = (e.x + e.y + e.z) / 3.0f;  // the sky's irradiance on a level plane
  // Light-sampling the sky pays when BSDF sampling finds its light badly (a large relative
  // variance V) and the sun, whose shadow rays it takes, lights a level plane little against
  // it (S / K). Picking the sun with p ≈ S / (S + K) adds S K to a level surface's variance and
  // cosine sampling leaves K² V, so the sky is worth its share when V > S / K; kSkyNeeMargin
  // is the measured offset (docs/rendering.md, "Light selection").
  const float s_level = sun * std::max(0.0f, sky.sun_direction().z);
  const bool sample_sky =
      !sky.empty() && k > 0.0f && sky.cosine_variance_up() > s_level / k + kSkyNeeMargin;
  const float skyv = sample_sky ? k : 0.0f;
  LightChoice c;
  c.sun = sun + skyv > 0.0f ? sun / (sun + skyv) : 0.0f;
  if (sun > 0.0f && skyv > 0.0f) c.sun = std::min(0.9f, std::max(0.1f, c.sun));
  c.sky = skyv > 0.0f ? 1.0f - c.sun : 0.0f;
  return c;
}

glm::vec3 surface_albedo(const WorldHit& hit) { return hit.material->albedo_at(hit.point()); }

Ray spawn_ray(const glm::vec3& p, const glm::vec3& ng, const glm::vec3& dir) {
  Ray r;
  const float side = glm::dot(dir, ng) >= 0.0f ? 1.0f : -1.0f;
  r.origin = p + ng * (side * ray_offset(p));
  r.direction = dir;
  return r;
}

float ray_offset(const glm::vec3& p) {
  const float m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return 2e-5f + 4e-6f * m;
}

PathSample PathIntegrator::trace(const Ray& camera_ray, const PixelSampler& sampler,
                                 std::uint32_t index) const {
  PathSample out;
  glm::vec3 beta(1.0f);
  Ray ray = camera_ray;
  float bsdf_pdf = 0.0f;  // of the direction just taken (0: camera ray, no MIS)
  for (int depth = 0;; ++depth) {
    WorldHit hit;
    ++out.rays;
    if (!world_.intersect(ray, hit)) {
      // Escaped: sky and sun, weighted against their own sampling where NEE could have found them.
      if (bsdf_pdf > 0.0f && choice_.sky > 0.0f) {  // else its weight is 1: no pdf needed
        const LightSample sky = sky_.lookup(ray.direction);
        out.radiance += beta * sky.radiance * power_heuristic(bsdf_pdf, choice_.sky * sky.pdf);
      } else {
        out.radiance += beta * sky_.radiance(ray.direction);
      }
      if (sky_.in_sun(ray.direction)) {
        const float w_sun =
            bsdf_pdf > 0.0f ? power_heuristic(bsdf_pdf, choice_.sun * sky_.sun_pdf()) : 1.0f;
        // Seen by the camera, the disk with its limb darkening; as a light, the uniform disk of the
        // same irradiance, as next-event estimation samples it (sky.h).
        out.radiance += beta *
                        (bsdf_pdf > 0.0f ? sky_.sun_radiance() : sky_.sun_radiance(ray.direction)) *
                        w_sun;
      }
      break;
    }
    const SurfaceHit& s = hit.surface;
    // pbrt-v4 regularises once a bounce was not specular; arbor has no specular (delta) lobe, so
    // every vertex after the camera's first hit.
    const materials::SurfaceBsdf sh = hit.material->bsdf(hit.point(regularize_ && depth > 0));
    if (depth == 0) first_hit(hit, sh, ray, sky_, out, beta);
    if (depth >= max_depth_) break;
    const ShadingFrame frame(sh.normal);
    const glm::dvec3 wo = frame.local(-ray.direction);
    const std::uint32_t dim = 2 + 4 * static_cast<std::uint32_t>(depth);

    // Next-event estimation: one light, the sun or the sky (light_choice()), or none.
    const bool pick_sun = picks_sun(choice_, sampler, index, dim);
    const glm::vec2 u_light = sampler.get2d(index, dim + 1);
    const float p_light = pick_sun ? choice_.sun : choice_.sky;
    LightSample ls;
    if (p_light > 0.0f) ls = pick_sun ? sky_.sample_sun(u_light) : sky_.sample(u_light);
    ls.pdf *= p_light;
    if (ls.pdf > 0.0f && (ls.radiance.x > 0.0f || ls.radiance.y > 0.0f || ls.radiance.z > 0.0f) &&
        (sh.transmits() ||
         glm::dot(ls.direction, s.geometric_normal) > 0.0f)) {  // not below an opaque surface
      const glm::dvec3 wi = frame.local(ls.direction);
      const glm::vec3 f = sh.eval(wo, wi);
      if (f.x > 0.0f || f.y > 0.0f || f.z > 0.0f) {
        ++out.rays;
        if (!world_.occluded(spawn_ray(s.position, s.geometric_normal, ls.direction))) {
          const float w = power_heuristic(ls.pdf, sh.pdf(wo, wi));
          out.radiance +=
              beta * f * ls.radiance * (static_cast<float>(std::fabs(wi.z)) * w / ls.pdf);
        }
      }
    }

    // Continue the path by sampling the BSDF.
    const glm::vec2 u = sampler.get2d(index, dim + 2);
    const glm::vec2 u2 = sampler.get2d(index, dim + 3);
    const materials::BsdfSample bs = sh.sample(wo, u, u2.x);
    if (bs.pdf <= 0.0) break;
    const glm::vec3 dir = glm::normalize(frame.world(bs.wi));
    const float cos_g = glm::dot(dir, s.geometric_normal);
    // A direction the shading normal allows but the geometry does not would leak light.
    if (!sh.transmits() && cos_g <= 0.0f) break;
    beta *= glm::vec3(bs.value) * static_cast<float>(std::fabs(bs.wi.z) / bs.pdf);
    bsdf_pdf = static_cast<float>(bs.pdf);
    // Russian roulette at the third and later vertices, survival √(largest throughput) up to 1
    // (Cycles' rule; docs/rendering.md: less variance and time than from the fourth vertex).
    if (depth >= 2) {
      const float q = std::min(1.0f, std::sqrt(std::max({beta.x, beta.y, beta.z})));
      if (u2.y >= q) break;
      beta /= q;
    }
    ray = spawn_ray(s.position, s.geometric_normal, dir);
  }
  return out;
}

}  // namespace arbor::tracer
