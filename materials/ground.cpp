// The ground's patches: smooth noise thresholded at the quantile that covers the asked fraction.
#include "materials/ground.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "materials/bark_noise.h"

namespace arbor::materials {

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
  // The order statistics a full sort would put at each quantile's index, without the sort.
  auto quantile = [&](double q) {
    const auto k =
        static_cast<std::ptrdiff_t>(std::min(v.size() - 1, static_cast<size_t>(q * v.size())));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<size_t>(k)];
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

glm::vec3 GroundMaterial::albedo_at(const SurfacePoint& p) const {
  const float w = patch(p.ground);
  return w > 0.0f ? albedo + (patch_albedo - albedo) * w : albedo;
}

}  // namespace arbor::materials
