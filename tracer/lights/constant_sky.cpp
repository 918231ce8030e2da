// A sky of one radiance in every direction (below the horizon too).
#include "tracer/lights/sky_model.h"

namespace arbor::tracer {

SkyMap constant_sky_map(const SkyContext& c) {
  SkyMap map;
  map.width = c.width;
  map.height = c.width / 2;
  map.texels.assign(static_cast<size_t>(map.width) * map.height,
                    glm::vec3(c.sky.color[0], c.sky.color[1], c.sky.color[2]));
  return map;
}

}  // namespace arbor::tracer
