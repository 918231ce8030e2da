// The film: a pixel's samples accumulated into its mean, the variance of that mean and the
// AOVs, and the tent filter that places samples.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "imaging/image.h"

namespace arbor::trace {

// Tent filter of radius 1 pixel: maps u in [0,1) to an offset in (-1, 1) distributed ∝ 1 - |x|.
float sample_tent(float u);

// An image of width × height with its AOV arrays allocated (zero) and `extras` integrator AOV
// floats a pixel.
Image make_image(int width, int height, std::size_t extras);

// One pixel's samples, in sample order (the order makes the sums bit-identical at any thread
// count): Welford's running mean and squared deviations of the beauty, sums of the AOVs.
class PixelAccumulator {
 public:
  explicit PixelAccumulator(std::size_t extras) : extra_sum_(extras) {}

  void reset();
  // A finite sample: beauty and albedo already in the output colour space.
  void add(const float rgb[3], const float albedo[3], const glm::vec3& normal, float depth,
           const float* extra);
  // Writes the pixel's mean, variance of the mean (sample variance / n) and AOV means to pixel
  // p of `image`; leaves it zero when no sample was finite.
  void store(Image& image, std::size_t p) const;

 private:
  int count_ = 0;
  glm::dvec3 mean_{0.0}, m2_{0.0}, albedo_{0.0}, normal_{0.0};
  double depth_ = 0.0;
  std::vector<double> extra_sum_;
};

}  // namespace arbor::trace
