// Pixel accumulation and the reconstruction filter.
#include "tracer/film.h"

#include <algorithm>
#include <cmath>

namespace arbor::trace {

float sample_tent(float u) {
  return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u);
}

Image make_image(int width, int height, std::size_t extras) {
  Image img;
  img.width = width;
  img.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  img.beauty.assign(n, glm::vec3(0.0f));
  img.variance.assign(n, glm::vec3(0.0f));
  img.albedo.assign(n, glm::vec3(0.0f));
  img.normal.assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.extra.assign(n * extras, 0.0f);
  return img;
}

void PixelAccumulator::reset() {
  count_ = 0;
  mean_ = m2_ = albedo_ = normal_ = glm::dvec3(0.0);
  depth_ = 0.0;
  std::fill(extra_sum_.begin(), extra_sum_.end(), 0.0);
}

void PixelAccumulator::add(const float rgb[3], const float alb[3], const glm::vec3& normal, float depth,
                           const float* extra) {
  // Welford's running mean and squared deviations.
  ++count_;
  const glm::dvec3 v(rgb[0], rgb[1], rgb[2]);
  const glm::dvec3 delta = v - mean_;
  mean_ += delta / static_cast<double>(count_);
  m2_ += delta * (v - mean_);
  albedo_ += glm::dvec3(alb[0], alb[1], alb[2]);
  normal_ += glm::dvec3(normal);
  depth_ += depth;
  for (std::size_t e = 0; e < extra_sum_.size(); ++e) extra_sum_[e] += extra[e];
}

void PixelAccumulator::store(Image& img, std::size_t p) const {
  if (count_ == 0) return;
  const std::size_t extras = extra_sum_.size();
  img.beauty[p] = glm::vec3(mean_);
  img.variance[p] = count_ > 1 ? glm::vec3(m2_ / (double(count_ - 1) * count_)) : glm::vec3(0.0f);
  img.albedo[p] = glm::vec3(albedo_ / double(count_));
  const glm::dvec3 nn = normal_ / double(count_);
  img.normal[p] = glm::vec3(nn);
  img.depth[p] = static_cast<float>(depth_ / count_);
  for (std::size_t e = 0; e < extras; ++e) img.extra[p * extras + e] = static_cast<float>(extra_sum_[e] / count_);
}

}  // namespace arbor::trace
