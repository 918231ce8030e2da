// Sampling a piecewise-constant 2D distribution: a marginal CDF over rows, a conditional CDF per
// row, each inverted by binary search.
#include "tracer/lights/distribution.h"

#include <algorithm>
#include <cmath>

namespace arbor::tracer {

Distribution2D::Distribution2D(const std::vector<float>& w, int width, int height)
    : width_(width), height_(height), weights_(w) {
  row_cdf_.assign(static_cast<size_t>(height) + 1, 0.0);
  col_cdf_.assign(static_cast<size_t>(height) * (width + 1), 0.0);
  for (int j = 0; j < height; ++j) {
    double* cdf = &col_cdf_[static_cast<size_t>(j) * (width + 1)];
    for (int i = 0; i < width; ++i) cdf[i + 1] = cdf[i] + w[static_cast<size_t>(j) * width + i];
    row_cdf_[static_cast<size_t>(j) + 1] = row_cdf_[static_cast<size_t>(j)] + cdf[width];
  }
  total_ = row_cdf_.back();
}

glm::vec2 Distribution2D::sample(glm::vec2 u, float& pdf) const {
  const double ru = u.y * total_;
  int j =
      static_cast<int>(std::upper_bound(row_cdf_.begin(), row_cdf_.end(), ru) - row_cdf_.begin()) -
      1;
  j = std::clamp(j, 0, height_ - 1);
  while (j > 0 && row_cdf_[static_cast<size_t>(j) + 1] == row_cdf_[static_cast<size_t>(j)]) --j;
  const double* cdf = &col_cdf_[static_cast<size_t>(j) * (width_ + 1)];
  const double row_total = cdf[width_];
  const double cu = u.x * row_total;
  int i = static_cast<int>(std::upper_bound(cdf, cdf + width_ + 1, cu) - cdf) - 1;
  i = std::clamp(i, 0, width_ - 1);
  const double wij = weights_[static_cast<size_t>(j) * width_ + i];
  const double fx = wij > 0.0 ? (cu - cdf[i]) / wij : 0.5;
  const double row_w = row_cdf_[static_cast<size_t>(j) + 1] - row_cdf_[static_cast<size_t>(j)];
  const double fy = row_w > 0.0 ? (ru - row_cdf_[static_cast<size_t>(j)]) / row_w : 0.5;
  pdf = static_cast<float>(wij / total_ * width_ * height_);
  return {static_cast<float>((i + std::clamp(fx, 0.0, 0.999999)) / width_),
          static_cast<float>((j + std::clamp(fy, 0.0, 0.999999)) / height_)};
}

float Distribution2D::pdf(glm::vec2 p) const {
  const int i = std::clamp(static_cast<int>(p.x * width_), 0, width_ - 1);
  const int j = std::clamp(static_cast<int>(p.y * height_), 0, height_ - 1);
  return static_cast<float>(weights_[static_cast<size_t>(j) * width_ + i] / total_ * width_ *
                            height_);
}

}  // namespace arbor::tracer
