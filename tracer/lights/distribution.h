// Importance sampling of tabulated functions: a piecewise-constant 2D distribution.
#pragma once

#include <vector>

#include <glm/vec2.hpp>

namespace arbor::tracer {

// Piecewise-constant 2D distribution over [0,1)² (rows × columns of weights).
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(const std::vector<float>& weights, int width, int height);
  // Maps u in [0,1)² to a point distributed ∝ weights; pdf with respect to area in [0,1)².
  glm::vec2 sample(glm::vec2 u, float& pdf) const;
  float pdf(glm::vec2 p) const;
  bool empty() const { return total_ <= 0.0; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<double> row_cdf_;  // height + 1
  std::vector<double> col_cdf_;  // height × (width + 1)
  std::vector<float> weights_;
  double total_ = 0.0;
};

}  // namespace arbor::tracer
