// Bark tiling and bump mapping: a point of a limb to its albedo, normal and BSDF.
#include "materials/bark.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "materials/bark_noise.h"

namespace arbor::materials {

namespace {
// Whole repeats of a tile round a limb of `radius` (the nearest to circumference / tile, so
// there is no seam), at least one.
double repeats_round(double radius, double tile) {
  return std::max(1.0, std::round(kTwoPi * radius / tile));
}
}  // namespace

double BarkMaterial::height(double along, double azimuth, double radius) const {
  if (!bump_map) return bark_height(along, azimuth, radius);
  const double repeats = repeats_round(radius, bump_tile);
  return bump_map->sample(azimuth / kTwoPi * repeats, along / bump_tile);
}

glm::vec3 BarkMaterial::bumped_normal(const SurfacePoint& p) const {
  const glm::vec3 n = p.shading_normal;
  if (bump_height <= 0.0f || p.radius <= 0.0f) return n;
  glm::vec3 t = p.tangent - n * glm::dot(p.tangent, n);
  if (glm::length(t) < 1e-6f) return n;
  t = glm::normalize(t);
  const glm::vec3 around = glm::cross(t, n);  // direction of increasing azimuth
  const double a = p.along, th = p.azimuth, r = p.radius, e = 0.002;
  const double h_along = (height(a + e, th, r) - height(a - e, th, r)) / (2 * e);
  const double h_around = (height(a, th + e / r, r) - height(a, th - e / r, r)) / (2 * e);
  // The trunk's base is furrowed deeper (up to 3× the relief at the ground).
  const double relief = bump_height * (1.0 + 2.0 * pattern.base(p.height));
  const glm::vec3 bumped =
      n - t * static_cast<float>(relief * h_along) - around * static_cast<float>(relief * h_around);
  return glm::normalize(bumped);
}

glm::vec3 BarkMaterial::albedo_at(const SurfacePoint& p) const {
  glm::vec3 a = albedo * p.color;
  if (albedo_map) {
    // Tiled like the bump map: whole repeats round the limb, every bump_tile metres along it.
    const double repeats = repeats_round(p.radius, bump_tile);
    a *= albedo_map->sample(p.azimuth / kTwoPi * repeats, p.along / bump_tile);
  } else if (pattern.any() && p.radius > 0.0f) {
    a = pattern.albedo(a, height(p.along, p.azimuth, p.radius), p.along, p.azimuth, p.radius,
                       p.height);
  }
  return a;
}

SurfaceBsdf BarkMaterial::bsdf(const SurfacePoint& p) const {
  return SurfaceBsdf::diffuse(bumped_normal(p), albedo_at(p), roughness);
}

}  // namespace arbor::materials
