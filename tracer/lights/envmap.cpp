// An environment map: a lat-long image (row 0 the zenith) read through OpenImageIO, scaled;
// negative texels are clamped to 0, non-finite ones refused.
#include <cmath>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <glm/common.hpp>

#include "common/error.h"
#include "common/input_file.h"
#include "tracer/lights/sky_model.h"

namespace arbor::tracer {

SkyMap envmap_sky_map(const SkyContext& c) {
  const scene::SkySpec& sky = c.sky;
  check_input_file(sky.path, "environment map");
  OIIO::ImageBuf image(sky.path);
  if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    throw InputError({sky.path, 0, 0}, "cannot read the environment map: " + image.geterror());
  }
  const OIIO::ImageSpec& spec = image.spec();
  SkyMap map;
  map.width = spec.width;
  map.height = spec.height;
  map.texels.resize(static_cast<size_t>(map.width) * map.height);
  std::vector<float> pixel(static_cast<size_t>(std::max(3, spec.nchannels)));
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      image.getpixel(i, j, pixel.data(), static_cast<int>(pixel.size()));
      const glm::vec3 colour =
          spec.nchannels >= 3 ? glm::vec3(pixel[0], pixel[1], pixel[2]) : glm::vec3(pixel[0]);
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
