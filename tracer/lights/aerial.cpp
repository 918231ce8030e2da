// The aerial perspective table: one march along each of the grid's directions, read at every
// slice's distance.
#include "tracer/lights/aerial.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/common.hpp>

#include "common/math.h"
#include "tracer/lights/nishita.h"

namespace arbor::tracer {

double AerialPerspective::slice_distance(int i) {
  const double u = double(i) / (kSlices - 1);
  return kMaxDistance * u * u;
}

glm::dvec3 AerialPerspective::cell_direction(int column, int row) {
  // Rows by v = ½ + ½ sign(e) √(|e| / 90°) of the elevation e: dense at the horizon, where the
  // air's depth changes fastest with the angle.
  const double phi = 2.0 * kPi * (column + 0.5) / kAzimuths, s = 2.0 * (row + 0.5) / kRows - 1.0;
  const double e = (s < 0.0 ? -1.0 : 1.0) * s * s * 0.5 * kPi;
  return {std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e)};
}

AerialPerspective::AerialPerspective(const NishitaSky& model,
                                     const std::function<glm::vec3(const glm::dvec3&)>& to_linear,
                                     double sun_y) {
  table_.resize(static_cast<size_t>(kRows) * kAzimuths * kSlices);
  std::vector<double> distances(kSlices);
  for (int i = 0; i < kSlices; ++i) distances[static_cast<size_t>(i)] = slice_distance(i);
  // Directions are independent: in parallel, each entry the same on any thread.
  tbb::parallel_for(
      tbb::blocked_range<int>(0, kRows * kAzimuths), [&](const tbb::blocked_range<int>& cells) {
        for (int cell = cells.begin(); cell < cells.end(); ++cell) {
          const glm::dvec3 d = cell_direction(cell % kAzimuths, cell / kAzimuths);
          const std::vector<NishitaSky::Segment> s = model.segments(d, distances, 4);
          for (int i = 0; i < kSlices; ++i) {
            Sample& out = table_[static_cast<size_t>(cell) * kSlices + i];
            const NishitaSky::Segment& g = s[static_cast<size_t>(i)];
            out.inscattered = glm::max(to_linear(g.inscattered), glm::vec3(0.0f));
            out.transmittance = glm::clamp(to_linear(g.transmitted) / static_cast<float>(sun_y),
                                           glm::vec3(0.0f), glm::vec3(1.0f));
          }
        }
      });
}

AerialPerspective::Sample AerialPerspective::at(const glm::vec3& direction, float distance) const {
  // Grid coordinates of the direction (cell centres at integer + 0.5); within a slice, linear in
  // the distance.
  float phi = std::atan2(direction.y, direction.x);
  if (phi < 0.0f) phi += 2.0f * static_cast<float>(kPi);
  const float x = phi / (2.0f * static_cast<float>(kPi)) * kAzimuths - 0.5f;
  const float e =
      std::asin(std::clamp(direction.z, -1.0f, 1.0f)) / (0.5f * static_cast<float>(kPi));
  const float v = 0.5f + 0.5f * std::copysign(std::sqrt(std::fabs(e)), e);
  const float y = v * kRows - 0.5f;
  const float d = std::clamp(distance, 0.0f, static_cast<float>(kMaxDistance));
  const int s0 =
      std::min(kSlices - 2,
               static_cast<int>(std::sqrt(d / static_cast<float>(kMaxDistance)) * (kSlices - 1)));
  const float d0 = static_cast<float>(slice_distance(s0)),
              d1 = static_cast<float>(slice_distance(s0 + 1));
  const float fx = std::floor(x);
  const int c0 = static_cast<int>(fx),
            r0 = std::clamp(static_cast<int>(std::floor(y)), 0, kRows - 2);
  const float wx = x - fx, wy = std::clamp(y - r0, 0.0f, 1.0f),
              wz = std::clamp((d - d0) / (d1 - d0), 0.0f, 1.0f);
  Sample out;
  out.transmittance = out.inscattered = glm::vec3(0.0f);
  for (int k = 0; k < 8; ++k) {
    const int c = ((c0 + (k & 1)) % kAzimuths + kAzimuths) % kAzimuths, r = r0 + ((k >> 1) & 1),
              s = s0 + (k >> 2);
    const float w = ((k & 1) ? wx : 1.0f - wx) * (((k >> 1) & 1) ? wy : 1.0f - wy) *
                    ((k >> 2) ? wz : 1.0f - wz);
    const Sample& e = table_[(static_cast<size_t>(r) * kAzimuths + c) * kSlices + s];
    out.transmittance += w * e.transmittance;
    out.inscattered += w * e.inscattered;
  }
  return out;
}

}  // namespace arbor::tracer
