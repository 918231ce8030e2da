#include "materials/leaf_texture.h"

#include <algorithm>
#include <cmath>

namespace arbor::materials {

namespace {

// 1 at distance ≤ inner, 0 at ≥ outer, smooth between.
float band(float distance, float inner, float outer) {
  const float x = std::clamp((outer - distance) / (outer - inner), 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

}  // namespace

float LeafTexture::mask(glm::vec2 uv) const {
  const float across = std::fabs(uv.x - 0.5f), v = std::clamp(uv.y, 0.0f, 1.0f);
  const float midrib_half = 0.025f * (1.0f - 0.7f * v);
  const float midrib = band(across, 0.5f * midrib_half, midrib_half);
  // Distance along v to the nearest secondary vein line v − 1.2 |u − ½| = k / pairs.
  const float phase = (v - 1.2f * across) * static_cast<float>(pairs);
  const float to_line = std::fabs(phase - std::round(phase)) / static_cast<float>(pairs);
  const float vein =
      band(to_line, 0.006f, 0.012f) * band(across, 0.30f, 0.42f) * (phase > 0.0f ? 1.0f : 0.0f);
  const float margin = 1.0f - band(across, 0.375f, 0.5f);
  return std::max({midrib, 0.7f * vein, 0.5f * margin});
}

glm::vec3 LeafTexture::tint(glm::vec2 uv) const {
  const float s = strength * mask(uv);
  return {std::exp(0.45f * s), std::exp(0.30f * s), std::exp(0.15f * s)};
}

}  // namespace arbor::materials
