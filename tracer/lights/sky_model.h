// The sky models: each makes the sky's lat-long radiance map (and, when its atmosphere colours the
// sun, the sun's irradiance at the ground). One file per model (preetham.cpp, constant_sky.cpp,
// envmap.cpp, nishita_map.cpp), one factory keyed by SkyModel (sky_model.cpp); the Sky (sky.h)
// samples whatever map it gets. A new model: its file, its case in the factory, its name in
// spec/scene_desc.h, its source in tracer/CMakeLists.txt.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "imaging/color.h"
#include "scene/render_input.h"

namespace arbor::tracer {

class AerialPerspective;

// What a model is made from.
struct SkyContext {
  const spec::SkyDesc& sky;
  const spec::SunDesc& sun;
  glm::dvec3 sun_direction;                      // unit, z up
  const imaging::ColorTransform& xyz_to_linear;  // CIE XYZ → scene-linear
  int width = 512;                               // of the map, for the models that compute theirs
  float rotation = 0.0f;                         // radians about z of the map's columns
  bool aerial_perspective = false;               // the air's table too (nishita, atmosphere)
};

// A lat-long map: `width` columns over the azimuth, `height` rows from the zenith (row 0) to the
// nadir, each texel the radiance at its centre.
struct SkyMap {
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;
  std::optional<glm::vec3> sun_irradiance;  // at the ground, when the model's atmosphere colours it
  // The atmosphere's aerial perspective, when the sky spec asks for it (never cached on disk)
  std::shared_ptr<const AerialPerspective> aerial;
};

// The map of `context.sky.model` (not SkyModel::None). InputError for an unreadable envmap.
SkyMap make_sky_map(const SkyContext& context);

// The direction of map coordinates p ∈ [0, 1)² (u along a row, v down the rows) rotated by
// `rotation` about z.
glm::vec3 lat_long_direction(glm::vec2 p, float rotation);

// Preetham, Shirley & Smits 1999 sky radiance as CIE XYZ (relative to a sun of irradiance
// `sun_irradiance`) for a view direction at zenith angle theta and angle gamma from the sun,
// with the sun at zenith angle theta_sun.
glm::dvec3 preetham_xyz(double turbidity, double theta, double gamma, double theta_sun,
                        double sun_irradiance);

}  // namespace arbor::tracer
