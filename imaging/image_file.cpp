// Reading every channel of an image for the comparison tools.
#include "imaging/image_file.h"

#include <cmath>

#include "common/error.h"

namespace arbor::imaging {

int ImageChannels::index(const std::string& name) const {
  for (int c = 0; c < image.channels; ++c) {
    if (image.channel_names[static_cast<std::size_t>(c)] == name) return c;
  }
  return -1;
}

float ImageChannels::finite(std::size_t p, int c, const char* what) const {
  const float v =
      image.pixels[p * static_cast<std::size_t>(image.channels) + static_cast<std::size_t>(c)];
  if (!std::isfinite(v)) {
    const std::size_t w = static_cast<std::size_t>(image.width);
    throw InputError({path, 0, 0}, std::string(what) + "pixel (" + std::to_string(p % w) + ", " +
                                       std::to_string(p / w) + ") is not a finite number");
  }
  return v;
}

ImageChannels read_image_channels(const std::string& path) {
  ImageChannels channels;
  channels.path = path;
  channels.image = read_image_file(path, "image", true);
  return channels;
}

}  // namespace arbor::imaging
