// Aerial perspective: what the air between the camera and a surface does to the surface's light —
// it dims it by the air's transmittance and adds the sunlight the air scatters towards the camera
// on the way — from the same atmosphere as the `nishita` or `atmosphere` sky (nishita.h), so that a
// forest 2 km away fades toward the horizon's colour. `[render] aerial_perspective = true`; off by
// default (docs/rendering.md, "Aerial perspective").
//
// A table over the direction from the camera (64 azimuths × 32 rows of elevation over the whole
// sphere, dense at the horizon) and the distance (32 slices at d = 100 km · (i / 31)²), each entry
// the transmittance and in-scattered radiance of the path from the camera to that distance, in
// the rendering space, white-balanced as the sky's map is; looked up trilinearly (linear in the
// distance). Beyond 100 km the last slice holds. The camera is taken to be at the sky's
// `altitude`: its own height in the scene is ignored, and below the horizon the air is taken at
// the ground's density (a path down into the Earth stands for one along the ground).
#pragma once

#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace arbor::tracer {

class NishitaSky;

class AerialPerspective {
 public:
  struct Sample {
    glm::vec3 transmittance{1.0f};  // of the surface's radiance, per channel
    glm::vec3 inscattered{0.0f};    // radiance added, scene-linear
  };
  static constexpr int kAzimuths = 64, kRows = 32, kSlices = 32;
  static constexpr double kMaxDistance = 100e3;  // metres

  // `to_linear`: CIE XYZ to the rendering space, white-balanced as the sky's map (the
  // extraterrestrial sun of luminance Y to (Y, Y, Y)); `sun_y`: that sun's Y.
  AerialPerspective(const NishitaSky& model,
                    const std::function<glm::vec3(const glm::dvec3&)>& to_linear, double sun_y);

  // The path from the camera along `direction` (unit) to a surface `distance` metres away.
  Sample at(const glm::vec3& direction, float distance) const;

  // The distance of slice i, and the direction at the centre of grid cell (column, row).
  static double slice_distance(int i);
  static glm::dvec3 cell_direction(int column, int row);

 private:
  std::vector<Sample> table_;  // [row][column][slice]
};

}  // namespace arbor::tracer
