// Sampling shared by the BSDFs (bsdf.h).
#include "materials/bsdf.h"

#include <algorithm>
#include <cmath>

#include "common/math.h"

namespace arbor::materials {

Dir sample_cosine_hemisphere(const glm::dvec2& u) {
  // The concentric map of the square to the disk, lifted to the hemisphere (Malley).
  const glm::dvec2 d = concentric_disk(u.x, u.y);
  const double x = d.x, y = d.y;
  return {x, y, std::sqrt(std::max(0.0, 1.0 - x * x - y * y))};
}

}  // namespace arbor::materials
