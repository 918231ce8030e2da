// The ground's patches: smooth noise thresholded at the quantile that covers the asked fraction.
#include "materials/ground.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/common.hpp>

#include "materials/bark_color.h"
#include "materials/bark_noise.h"

namespace arbor::materials {

double GroundMaterial::noise(double x, double y) {
  // Three octaves of gradient noise on the plane, each at its own height of the noise's lattice.
  return 0.6 * gradient_noise(x, y, 0.37) + 0.3 * gradient_noise(2.03 * x, 2.03 * y, 1.91) +
         0.1 * gradient_noise(4.11 * x, 4.11 * y, 3.43);
}

void GroundMaterial::quantiles(float c, double& threshold_out, double& edge_out) {
  std::vector<double> v;
  v.reserve(512 * 512);
  for (int i = 0; i < 512; ++i) {
    for (int j = 0; j < 512; ++j) v.push_back(noise(i * 0.137, j * 0.137));  // 70 × 70 scales
  }
  // The order statistics a full sort would put at each quantile's index, without the sort.
  auto quantile = [&](double q) {
    const auto k =
        static_cast<std::ptrdiff_t>(std::min(v.size() - 1, static_cast<size_t>(q * v.size())));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<size_t>(k)];
  };
  threshold_out = c >= 1.0f ? -1e9 : quantile(1.0 - c);
  edge_out = 0.25 * (quantile(0.84) - quantile(0.16));  // a quarter of the noise's spread
}

void GroundMaterial::set_cover(float c) {
  cover = c;
  if (c > 0.0f) quantiles(c, threshold, edge);
}

void GroundMaterial::set_litter(float c) {
  litter = c;
  if (c > 0.0f) quantiles(c, litter_threshold, litter_edge);
}

namespace {
double smooth(double e) {
  e = std::clamp(e, 0.0, 1.0);
  return e * e * (3.0 - 2.0 * e);
}
}  // namespace

float GroundMaterial::litter_weight(glm::vec2 xy) const {
  if (litter <= 0.0f) return 0.0f;
  // The patches' noise at half their scale, shifted to where it is independent of theirs.
  const double n = noise(2.0 * xy.x / scale + 57.3, 2.0 * xy.y / scale - 31.9);
  return static_cast<float>(smooth((n - litter_threshold) / (2.0 * litter_edge) + 0.5));
}

glm::vec3 GroundMaterial::detailed(glm::vec3 soil, glm::vec3 grass, float w, glm::vec2 xy) const {
  if (detail > 0.0f) {
    // Brightness by three finer octaves (about ±0.5 of the noise, mean 0): clods and tufts.
    const double x = xy.x / scale, y = xy.y / scale;
    const double n = 0.5 * gradient_noise(4.0 * x, 4.0 * y, 5.17) +
                     0.3 * gradient_noise(13.0 * x, 13.0 * y, 6.31) +
                     0.2 * gradient_noise(50.0 * x, 50.0 * y, 7.73);
    const float m = 1.0f + 0.8f * detail * static_cast<float>(n);
    soil *= m;
    grass *= m;
    // Drier, yellower grass where a coarser noise is high.
    const float dry = static_cast<float>(smooth(gradient_noise(3.0 * x, 3.0 * y, 8.91) / 0.4));
    grass = glm::mix(grass, glm::vec3(0.10f, 0.11f, 0.04f) * m, 0.6f * detail * dry);
  }
  glm::vec3 a = soil + (grass - soil) * w;
  if (stones > 0.0f) {
    // Stones 2–6 cm across (0.6–1.4 × 4 × 3 cm) on the soil.
    const float s = mark_coverage_plane(xy.x, xy.y, stones, 0.04f, 0.03f, 0x73746fu);
    a = glm::mix(a, stone_albedo, (1.0f - w) * s);
  }
  return litter > 0.0f ? glm::mix(a, litter_albedo, litter_weight(xy)) : a;
}

float GroundMaterial::patch(glm::vec2 xy) const {
  if (cover <= 0.0f) return 0.0f;
  // A smoothstep of the noise across [threshold − edge, threshold + edge]: soft-edged patches.
  const double e =
      std::clamp((noise(xy.x / scale, xy.y / scale) - threshold) / (2.0 * edge) + 0.5, 0.0, 1.0);
  return static_cast<float>(e * e * (3.0 - 2.0 * e));
}

glm::vec3 GroundMaterial::rock_at(glm::vec2 xy) const {
  const double x = xy.x, y = xy.y;
  // Brightness ±25 % by a 2 m and a 30 cm octave; lichen (grey-green, brighter) on a third.
  const double n =
      0.6 * gradient_noise(x / 2.0, y / 2.0, 9.13) + 0.4 * gradient_noise(x / 0.3, y / 0.3, 9.71);
  const glm::vec3 a = rock_albedo * static_cast<float>(1.0 + 0.5 * n);
  const float lichen =
      static_cast<float>(smooth((gradient_noise(x / 0.6, y / 0.6, 10.37) - 0.1) / 0.3 + 0.5));
  return glm::mix(a, glm::vec3(0.36f, 0.38f, 0.27f), 0.7f * lichen);
}

glm::vec3 GroundMaterial::albedo_at(const SurfacePoint& p) const {
  const float w = patch(p.ground);
  glm::vec3 a;
  if (detail > 0.0f || stones > 0.0f || litter > 0.0f)
    a = detailed(albedo, patch_albedo, w, p.ground);
  else
    a = w > 0.0f ? albedo + (patch_albedo - albedo) * w : albedo;
  if (!terrain || (p.terrain.x <= 0.0f && p.terrain.y <= 0.0f)) return a;
  a = glm::mix(a, soil_albedo, p.terrain.x);
  return p.terrain.y > 0.0f ? glm::mix(a, rock_at(p.ground), p.terrain.y) : a;
}

}  // namespace arbor::materials
