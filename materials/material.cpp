// Bark tiling, bump mapping and leaf tints: surface points to BSDF values.
#include "materials/material.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
  const glm::vec3 bumped = n - t * static_cast<float>(bump_height * h_along) -
                           around * static_cast<float>(bump_height * h_around);
  return glm::normalize(bumped);
}

glm::vec3 BarkMaterial::albedo_at(const SurfacePoint& p) const {
  glm::vec3 a = albedo * p.color;
  if (albedo_map) {
    // Tiled like the bump map: whole repeats round the limb, every bump_tile metres along it.
    const double repeats = repeats_round(p.radius, bump_tile);
    a *= albedo_map->sample(p.azimuth / kTwoPi * repeats, p.along / bump_tile);
  }
  return a;
}

glm::vec3 LeafMaterial::tint(const SurfacePoint& p) const {
  const glm::vec3 tex = albedo_map ? albedo_map->sample(p.uv.x, p.uv.y) : glm::vec3(1.0f);
  return tex * p.color;
}

glm::vec3 LeafMaterial::reflectance(const SurfacePoint& p) const {
  const glm::vec3 side = p.leaf_back ? back : front;
  return tinted ? side * tint(p) : side;
}

double GroundMaterial::noise(double x, double y) {
  // Three octaves of gradient noise on the plane, each at its own height of the noise's lattice.
  return 0.6 * gradient_noise(x, y, 0.37) + 0.3 * gradient_noise(2.03 * x, 2.03 * y, 1.91) +
         0.1 * gradient_noise(4.11 * x, 4.11 * y, 3.43);
}

void GroundMaterial::set_cover(float c) {
  cover = c;
  if (c <= 0.0f) return;
  std::vector<double> v;
  v.reserve(512 * 512);
  for (int i = 0; i < 512; ++i) {
    for (int j = 0; j < 512; ++j) v.push_back(noise(i * 0.137, j * 0.137));  // 70 × 70 scales
  }
  std::sort(v.begin(), v.end());
  auto quantile = [&](double q) {
    return v[std::min(v.size() - 1, static_cast<size_t>(q * v.size()))];
  };
  threshold = c >= 1.0f ? -1e9 : quantile(1.0 - c);
  edge = 0.25 * (quantile(0.84) - quantile(0.16));  // a quarter of the noise's spread
}

float GroundMaterial::patch(glm::vec2 xy) const {
  if (cover <= 0.0f) return 0.0f;
  // A smoothstep of the noise across [threshold − edge, threshold + edge]: soft-edged patches.
  const double e =
      std::clamp((noise(xy.x / scale, xy.y / scale) - threshold) / (2.0 * edge) + 0.5, 0.0, 1.0);
  return static_cast<float>(e * e * (3.0 - 2.0 * e));
}

SurfaceBsdf Material::bsdf(const SurfacePoint& p) const {
  SurfaceBsdf b;
  b.normal = p.shading_normal;
  OrenNayar diffuse;
  switch (kind) {
    case Kind::Diffuse: diffuse.albedo = glm::dvec3(albedo); break;
    case Kind::Ground: diffuse.albedo = glm::dvec3(albedo_at(p)); break;
    case Kind::Bark:
      diffuse.albedo = glm::dvec3(bark.albedo_at(p));
      diffuse.sigma = bark.roughness;
      b.normal = bark.bumped_normal(p);
      break;
    case Kind::Leaf: {
      const glm::vec3 t = leaf.tinted ? leaf.tint(p) : glm::vec3(1.0f);
      const glm::vec3 side = p.leaf_back ? leaf.back : leaf.front;
      LeafBsdf l;
      l.reflectance = glm::dvec3(leaf.tinted ? side * t : side);
      l.transmittance = glm::dvec3(leaf.tinted ? leaf.transmittance * t : leaf.transmittance);
      l.coat = leaf.cuticle.get();
      b.lobes = l;
      b.albedo = glm::vec3(l.reflectance);
      break;
    }
  }
  if (kind != Kind::Leaf) {
    b.lobes = diffuse;
    b.albedo = glm::vec3(diffuse.albedo);
  }
  if (glm::dot(b.normal, p.geometric_normal) < 0.0f) b.normal = -b.normal;
  return b;
}

glm::vec3 Material::albedo_at(const SurfacePoint& p) const {
  switch (kind) {
    case Kind::Diffuse: return albedo;
    case Kind::Ground: {
      const float w = ground.patch(p.ground);
      return w > 0.0f ? albedo + (ground.patch_albedo - albedo) * w : albedo;
    }
    case Kind::Bark: return bark.albedo_at(p);
    case Kind::Leaf: return leaf.reflectance(p);
  }
  return albedo;
}

}  // namespace arbor::materials
