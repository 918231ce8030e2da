// Leaf tints: a point of a leaf to its reflectance, transmittance and two-sided BSDF.
#include "materials/leaf.h"

namespace arbor::materials {

glm::vec3 LeafMaterial::tint(const SurfacePoint& p) const {
  const glm::vec3 tex = albedo_map ? albedo_map->sample(p.uv.x, p.uv.y) : glm::vec3(1.0f);
  glm::vec3 t = tex * p.color;
  if (texture.any()) t *= texture.tint(p.uv);
  if (season.any()) t *= season.tint(p.leaf_key);
  return variation.any() ? t * variation.tint(p.leaf_key, p.crown_height) : t;
}

glm::vec3 LeafMaterial::albedo_at(const SurfacePoint& p) const { return bsdf(p).albedo; }

SurfaceBsdf LeafMaterial::bsdf(const SurfacePoint& p) const {
  const glm::vec3 t = tinted ? tint(p) : glm::vec3(1.0f);
  const glm::vec3 side = p.leaf_back ? back : front;
  LeafBsdf l;
  l.reflectance = glm::dvec3(tinted ? side * t : side);
  l.transmittance = glm::dvec3(tinted ? transmittance * t : transmittance);
  for (int c = 0; c < 3; ++c) {
    const double sum = l.reflectance[c] + l.transmittance[c];
    if (sum > 1.0) {
      l.reflectance[c] /= sum;
      l.transmittance[c] /= sum;
    }
  }
  l.coat = p.regularize && regularized ? regularized : cuticle;
  SurfaceBsdf b;
  b.lobes = l;
  b.normal = p.shading_normal;
  b.albedo = glm::vec3(l.reflectance);
  return b;
}

}  // namespace arbor::materials
