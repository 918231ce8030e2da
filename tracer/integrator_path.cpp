// Path tracing with NEE + MIS + Russian roulette. Materials are evaluated into plain BSDF values
// at each hit; nothing is allocated per sample.
#include "tracer/integrator_path.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "materials/bark_noise.h"
#include "materials/leaf_bsdf.h"
#include "materials/oren_nayar.h"

namespace arbor::trace {

namespace {

float power_heuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

// Orthonormal shading frame around n (z); directions are converted to and from it.
struct Frame {
  glm::vec3 x, y, z;
  explicit Frame(const glm::vec3& n) : z(n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    x = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    y = glm::vec3(b, sign + n.y * n.y * a, -n.y);
  }
  glm::dvec3 local(const glm::vec3& v) const {
    return {glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)};
  }
  glm::vec3 world(const glm::dvec3& v) const {
    return x * static_cast<float>(v.x) + y * static_cast<float>(v.y) + z * static_cast<float>(v.z);
  }
};

// The BSDF at a hit: opaque diffuse (bark, ground; Oren–Nayar, Lambertian at σ = 0) or a
// two-sided leaf.
struct Shading {
  bool leaf = false;
  mat::OrenNayar lambert;
  mat::LeafBsdf leaf_bsdf;
  glm::vec3 normal{0.0f};  // shading normal, on the side the ray came from
  glm::vec3 albedo{0.0f};

  glm::vec3 eval(const glm::dvec3& wo, const glm::dvec3& wi) const {
    return glm::vec3(leaf ? leaf_bsdf.eval(wo, wi) : lambert.eval(wo, wi));
  }
  float pdf(const glm::dvec3& wo, const glm::dvec3& wi) const {
    return static_cast<float>(leaf ? leaf_bsdf.pdf(wo, wi) : lambert.pdf(wo, wi));
  }
};

// Bark height in [0, 1]: the user's image, repeated every bump_tile metres along the limb and a
// whole number of times round it (the nearest to circumference / bump_tile, so there is no seam),
// or the procedural furrows.
double bark_height(const TreeLook& look, double along, double azimuth, double radius) {
  if (!look.bump_map) return mat::bark_height(along, azimuth, radius);
  constexpr double kTwoPi = 6.283185307179586;
  const double repeats = std::max(1.0, std::round(kTwoPi * radius / look.bump_tile));
  return look.bump_map->sample(azimuth / kTwoPi * repeats, along / look.bump_tile);
}

// Bark bump mapping (bump_height metres of relief): the normal tilts against the height
// gradient along the limb and around it.
glm::vec3 bumped_normal(const SurfaceHit& s, const TreeLook& look) {
  const glm::vec3 n = s.shading_normal;
  const float bump_height = look.bump_height;
  if (bump_height <= 0.0f || s.bark.radius <= 0.0f) return n;
  glm::vec3 t = s.tangent - n * glm::dot(s.tangent, n);
  if (glm::length(t) < 1e-6f) return n;
  t = glm::normalize(t);
  const glm::vec3 around = glm::cross(t, n);  // direction of increasing azimuth
  const double a = s.bark.along, th = s.bark.azimuth, r = s.bark.radius, e = 0.002;
  const double h_along = (bark_height(look, a + e, th, r) - bark_height(look, a - e, th, r)) / (2 * e);
  const double h_around =
      (bark_height(look, a, th + e / r, r) - bark_height(look, a, th - e / r, r)) / (2 * e);
  const glm::vec3 bumped = n - t * static_cast<float>(bump_height * h_along) -
                           around * static_cast<float>(bump_height * h_around);
  return glm::normalize(bumped);
}

// What multiplies a leaf's reflectance and transmittance: its albedo map and primitive colour.
glm::vec3 leaf_tint(const TreeLook& look, const SurfaceHit& s) {
  const glm::vec3 tex = look.leaf_albedo_map ? look.leaf_albedo_map->sample(s.uv.x, s.uv.y) : glm::vec3(1.0f);
  return tex * s.color;
}

// The reflectance of the leaf side the ray hit.
glm::vec3 leaf_side(const TreeLook& look, const SurfaceHit& s) {
  return s.material == gen::kMaterialLeafBack ? look.leaf_back : look.leaf_front;
}

glm::vec3 bark_albedo(const TreeLook& look, const SurfaceHit& s) {
  glm::vec3 albedo = look.bark_albedo * s.color;
  if (look.bark_albedo_map) {
    // Tiled like the bump map: whole repeats round the limb, every bump_tile metres along it.
    constexpr double kTwoPi = 6.283185307179586;
    const double repeats = std::max(1.0, std::round(kTwoPi * s.bark.radius / look.bump_tile));
    albedo *= look.bark_albedo_map->sample(s.bark.azimuth / kTwoPi * repeats, s.bark.along / look.bump_tile);
  }
  return albedo;
}

Shading shade(const World& world, const WorldHit& hit) {
  Shading sh;
  const SurfaceHit& s = hit.surface;
  sh.normal = s.shading_normal;
  if (hit.ground) {
    sh.lambert.albedo = glm::dvec3(world.ground_albedo());
  } else if (hit.mesh) {
    const MeshLook& m = *hit.mesh;
    if (m.kind == MeshLook::Kind::Leaf) {
      sh.leaf = true;
      sh.leaf_bsdf.reflectance = glm::dvec3(hit.mesh_front ? m.leaf_front : m.leaf_back);
      sh.leaf_bsdf.transmittance = glm::dvec3(m.leaf_transmittance);
    } else {
      sh.lambert.albedo = glm::dvec3(m.albedo);
    }
  } else {
    const TreeLook& look = world.look(hit.instance);
    if (s.kind == SurfaceKind::Leaf) {
      sh.leaf = true;
      const glm::vec3 tint = leaf_tint(look, s);
      sh.leaf_bsdf.reflectance = glm::dvec3(leaf_side(look, s) * tint);
      sh.leaf_bsdf.transmittance = glm::dvec3(look.leaf_transmittance * tint);
    } else {
      sh.lambert.albedo = glm::dvec3(bark_albedo(look, s));
      sh.lambert.sigma = look.bark_roughness;
      sh.normal = bumped_normal(s, look);
    }
  }
  if (glm::dot(sh.normal, s.geometric_normal) < 0.0f) sh.normal = -sh.normal;
  sh.albedo = sh.leaf ? glm::vec3(sh.leaf_bsdf.reflectance) : glm::vec3(sh.lambert.albedo);
  return sh;
}

}  // namespace

glm::vec3 surface_albedo(const World& world, const WorldHit& hit) {
  if (hit.ground) return world.ground_albedo();
  if (hit.mesh) {
    const MeshLook& m = *hit.mesh;
    if (m.kind != MeshLook::Kind::Leaf) return m.albedo;
    return hit.mesh_front ? m.leaf_front : m.leaf_back;
  }
  const TreeLook& look = world.look(hit.instance);
  const SurfaceHit& s = hit.surface;
  return s.kind == SurfaceKind::Leaf ? leaf_side(look, s) * leaf_tint(look, s) : bark_albedo(look, s);
}

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
      const glm::vec3 sky = sky_.radiance(ray.direction);
      const float w_sky = bsdf_pdf > 0.0f ? power_heuristic(bsdf_pdf, sky_.pdf(ray.direction)) : 1.0f;
      out.radiance += beta * sky * w_sky;
      if (sky_.in_sun(ray.direction)) {
        const float w_sun = bsdf_pdf > 0.0f ? power_heuristic(bsdf_pdf, sky_.sun_pdf()) : 1.0f;
        out.radiance += beta * sky_.sun_radiance() * w_sun;
      }
      break;
    }
    const SurfaceHit& s = hit.surface;
    const Shading sh = shade(world_, hit);
    if (depth == 0) {
      out.albedo = sh.albedo;
      out.normal = sh.normal;
      out.depth = s.t;
    }
    if (depth >= max_depth_) break;
    const Frame frame(sh.normal);
    const glm::dvec3 wo = frame.local(-ray.direction);
    const std::uint32_t dim = 2 + 4 * static_cast<std::uint32_t>(depth);

    // Next-event estimation: one sample of the sun and one of the sky, each with MIS.
    const LightSample lights[2] = {sky_.sample_sun(sampler.get2d(index, dim)),
                                   sky_.sample(sampler.get2d(index, dim + 1))};
    for (int k = 0; k < 2; ++k) {
      const LightSample& ls = lights[k];
      if (ls.pdf <= 0.0f || (ls.radiance.x <= 0.0f && ls.radiance.y <= 0.0f && ls.radiance.z <= 0.0f)) continue;
      const float cos_g = glm::dot(ls.direction, s.geometric_normal);
      if (!sh.leaf && cos_g <= 0.0f) continue;  // below an opaque surface
      const glm::dvec3 wi = frame.local(ls.direction);
      const glm::vec3 f = sh.eval(wo, wi);
      if (f.x <= 0.0f && f.y <= 0.0f && f.z <= 0.0f) continue;
      ++out.rays;
      if (world_.occluded(spawn_ray(s.position, s.geometric_normal, ls.direction))) continue;
      const float w = power_heuristic(ls.pdf, sh.pdf(wo, wi));
      out.radiance += beta * f * ls.radiance * (static_cast<float>(std::fabs(wi.z)) * w / ls.pdf);
    }

    // Continue the path by sampling the BSDF.
    const glm::vec2 u = sampler.get2d(index, dim + 2);
    const glm::vec2 u2 = sampler.get2d(index, dim + 3);
    mat::BsdfSample bs;
    if (sh.leaf) {
      bs = sh.leaf_bsdf.sample(wo, glm::dvec3(u2.x, u.x, u.y));
    } else {
      bs = sh.lambert.sample(wo, glm::dvec2(u.x, u.y));
    }
    if (bs.pdf <= 0.0) break;
    const glm::vec3 dir = glm::normalize(frame.world(bs.wi));
    const float cos_g = glm::dot(dir, s.geometric_normal);
    // A direction the shading normal allows but the geometry does not would leak light.
    if (!sh.leaf && cos_g <= 0.0f) break;
    beta *= glm::vec3(bs.value) * static_cast<float>(std::fabs(bs.wi.z) / bs.pdf);
    bsdf_pdf = static_cast<float>(bs.pdf);
    // Russian roulette after three bounces, survival by throughput.
    if (depth >= 3) {
      const float q = std::min(0.95f, std::max({beta.x, beta.y, beta.z}));
      if (u2.y >= q) break;
      beta /= q;
    }
    ray = spawn_ray(s.position, s.geometric_normal, dir);
  }
  return out;
}

}  // namespace arbor::trace
