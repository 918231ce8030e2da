// TREE-MAKER's five-factor shade (Neighbors & Hodges §III, Figure 3) at the first hit, and the
// ground shadow.
#include "tracer/integrators/treemaker.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "common/frame.h"
#include "tracer/integrators/path.h"

namespace arbor::tracer {

TreemakerTerms treemaker_terms(const scene::TreeExtent& tree, const glm::vec3& p,
                               const glm::vec3& n, bool line, const glm::vec3& to_light) {
  TreemakerTerms t{};
  t[0] = 1.0f;
  const float nl = glm::dot(n, to_light);
  t[1] = line ? std::sqrt(std::max(0.0f, 1.0f - nl * nl)) : std::fabs(nl);
  t[2] = (p.z - tree.base.z) / tree.height;
  const glm::vec2 out(p.x - tree.base.x, p.y - tree.base.y);
  const float r = glm::length(out);
  t[3] = r / tree.radius;
  const glm::vec2 sun(to_light.x, to_light.y);
  const float sun_len = glm::length(sun);
  if (r > 1e-6f && sun_len > 1e-6f) {
    // q = π − φ with cos φ = out·sun: sin(q/2) = cos(φ/2) = sqrt((1 + cos φ) / 2).
    const float cos_phi = std::clamp(glm::dot(out, sun) / (r * sun_len), -1.0f, 1.0f);
    t[4] = std::sqrt(0.5f * (1.0f + cos_phi));
  } else {
    t[4] = std::sqrt(0.5f);  // q = π/2
  }
  return t;
}

float treemaker_shade(const materials::TreemakerWeights& w, const TreemakerTerms& t) {
  return static_cast<float>(w.ambient * t[0] + w.lambert * t[1] + w.height * t[2] +
                            w.radius * t[3] + w.angle * t[4]);
}

void TreemakerSample::write_aovs(float exposure, const imaging::ColorTransform& to_output,
                                 float* out) const {
  std::size_t k = 0;
  for (float term : terms) out[k++] = term;
  auto put = [&](const glm::vec3& c) {
    float rgb[3] = {c.x * exposure, c.y * exposure, c.z * exposure};
    to_output(rgb);
    for (float v : rgb) out[k++] = v;
  };
  for (const glm::vec3& c : contribution) put(c);
  put(rest);
}

TreemakerIntegrator::TreemakerIntegrator(const World& world, const Sky& sky)
    : world_(world), sky_(sky) {
  if (sky.has_sun()) {
    to_light_ = sky.sun_direction();
    sun_irradiance_ = sky.sun_irradiance_color();
  }
  sky_irradiance_ = sky.irradiance_up();
  max_intensity_ = (sun_irradiance_ + sky_irradiance_) / static_cast<float>(kPi);
}

glm::vec3 TreemakerIntegrator::diffuse_radiance(const WorldHit& hit, std::uint32_t& rays) const {
  const SurfaceHit& s = hit.surface;
  glm::vec3 e = sky_irradiance_;
  const float cos_sun = glm::dot(s.geometric_normal, to_light_);
  if (sun_irradiance_ != glm::vec3(0.0f) && cos_sun > 0.0f) {
    // The paper casts the tree's points onto the ground along the sun direction and paints them
    // in the ground's shadow colour; for a distant sun a shadow ray from the ground point finds
    // exactly the points that projection covers. The shadow colour is the ground lit by the sky
    // alone.
    ++rays;
    if (!world_.occluded(spawn_ray(s.position, s.geometric_normal, to_light_)))
      e += sun_irradiance_ * cos_sun;
  }
  return surface_albedo(hit) * e / static_cast<float>(kPi);
}

TreemakerSample TreemakerIntegrator::trace(const Ray& ray) const {
  TreemakerSample out;
  PathSample& shade = out.shade;
  WorldHit hit;
  ++shade.rays;
  if (!world_.intersect(ray, hit)) {
    shade.radiance = sky_.radiance(ray.direction);
    if (sky_.in_sun(ray.direction)) shade.radiance += sky_.sun_radiance(ray.direction);
    out.rest = shade.radiance;
    return out;
  }
  const SurfaceHit& s = hit.surface;
  shade.albedo = surface_albedo(hit);
  shade.normal = s.shading_normal;
  shade.depth = s.t;
  shade.hit = true;
  shade.object_id = hit.object_id;
  shade.material_id = hit.material_id;
  if (hit.instance < 0) {
    shade.radiance = out.rest = diffuse_radiance(hit, shade.rays);
    return out;
  }
  const bool line = s.kind != SurfaceKind::Leaf;  // limbs, trunk grids and line elements
  out.terms = treemaker_terms(world_.extent(hit.instance), s.position,
                              line ? s.tangent : s.geometric_normal, line, to_light_);
  const materials::TreemakerWeights& w = world_.instance(hit.instance).treemaker;
  const double weights[5] = {w.ambient, w.lambert, w.height, w.radius, w.angle};
  const glm::vec3 unit = shade.albedo * max_intensity_;
  for (int i = 0; i < 5; ++i) {
    out.contribution[static_cast<size_t>(i)] = unit * out.terms[static_cast<size_t>(i)];
    shade.radiance += out.contribution[static_cast<size_t>(i)] * static_cast<float>(weights[i]);
  }
  return out;
}

}  // namespace arbor::tracer
