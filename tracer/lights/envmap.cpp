// An environment map: a lat-long image (row 0 the zenith) read through OpenImageIO, scaled;
// negative texels are clamped to 0, non-finite ones refused.
#include <cmath>
#include <vector>

#include <glm/common.hpp>

#include "common/error.h"
#include "common/image_library.h"
#include "tracer/lights/sky_model.h"

namespace arbor::tracer {

SkyMap envmap_sky_map(const SkyContext& c) {
  const spec::SkyDesc& sky = c.sky;
  DecodedImage image = read_image_file(sky.path, "environment map", true);
  SkyMap map;
  map.width = image.width;
  map.height = image.height;
  map.texels.resize(static_cast<size_t>(map.width) * map.height);
  const std::size_t channels = static_cast<std::size_t>(image.channels);
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      const float* pixel = &image.pixels[(static_cast<size_t>(j) * map.width + i) * channels];
      const glm::vec3 colour =
          channels >= 3 ? glm::vec3(pixel[0], pixel[1], pixel[2]) : glm::vec3(pixel[0]);
      if (!std::isfinite(colour.x) || !std::isfinite(colour.y) || !std::isfinite(colour.z)) {
        throw InputError({sky.path, 0, 0}, "the environment map has a pixel that is not finite");
      }
      map.texels[static_cast<size_t>(j) * map.width + i] =
          glm::max(colour, glm::vec3(0.0f)) * static_cast<float>(sky.scale);
    }
  }
  return map;
}

}  // namespace arbor::tracer
