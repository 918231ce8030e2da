#include "materials/leaf_variation.h"

#include <algorithm>
#include <cmath>

#include "common/math.h"
#include "common/rng.h"

namespace arbor::materials {

glm::vec3 LeafVariation::tint(std::uint64_t key, float crown_height) const {
  // Two standard normal variates by Box–Muller from the leaf's own stream.
  Rng rng(key);
  const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();  // u1 in (0, 1]
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double z1 = std::clamp(r * std::cos(2.0 * kPi * u2), -3.0, 3.0);
  const double z2 = std::clamp(r * std::sin(2.0 * kPi * u2), -3.0, 3.0);
  const double v = value, h = hue;
  const double common = v * z1 - 0.5 * v * v + crown * (crown_height - 0.5);
  constexpr double kAxis[3] = {1.0, 0.35, 0.0};  // arbor's chlorophyll axis in ln RGB
  glm::vec3 t;
  for (int c = 0; c < 3; ++c) {
    const double d = kAxis[c];
    t[c] = static_cast<float>(std::exp(common + d * (h * z2 - 0.5 * h * h * d)));
  }
  return t;
}

glm::vec3 LeafSeason::tint(std::uint64_t key) const {
  glm::vec3 t = spring;
  if (turned > 0.0f) {
    Rng rng(derive_key(key, 0x5ea5011u));  // a stream apart from the variation's
    if (rng.uniform() < turned) {
      // Pigments absorb, so a leaf part-way between its summer and autumn pigments has the
      // geometric mean of their reflectances (Beer–Lambert: absorbances add): autumn^m.
      const double m = kLeastTurn + (1.0 - kLeastTurn) * rng.uniform();
      for (int c = 0; c < 3; ++c) t[c] *= static_cast<float>(std::pow(double(autumn[c]), m));
    }
  }
  return t;
}

}  // namespace arbor::materials
