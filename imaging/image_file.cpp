// Reading every channel of an image for the comparison tools.
#include "imaging/image_file.h"

#include <cmath>

#include <OpenImageIO/imageio.h>

#include "common/error.h"
#include "common/input_file.h"

namespace arbor::imaging {

int ImageChannels::index(const std::string& name) const {
  for (int c = 0; c < spec.nchannels; ++c) {
    if (spec.channelnames[static_cast<std::size_t>(c)] == name) return c;
  }
  return -1;
}

float ImageChannels::finite(std::size_t p, int c, const char* what) const {
  const float v = data[p * static_cast<std::size_t>(spec.nchannels) + static_cast<std::size_t>(c)];
  if (!std::isfinite(v)) {
    const std::size_t w = static_cast<std::size_t>(spec.width);
    throw InputError({path, 0, 0}, std::string(what) + "pixel (" + std::to_string(p % w) + ", " +
                                       std::to_string(p / w) + ") is not a finite number");
  }
  return v;
}

ImageChannels read_image_channels(const std::string& path) {
  check_input_file(path, "image");
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "cannot be read as an image";
    throw InputError({path, 0, 0}, "cannot read the image: " + why);
  }
  ImageChannels image;
  image.path = path;
  image.spec = in->spec();
  const OIIO::ImageSpec& spec = image.spec;
  if (spec.width <= 0 || spec.height <= 0 ||
      static_cast<long long>(spec.width) * spec.height > (1LL << 28)) {
    throw InputError({path, 0, 0}, "has an unsupported size " + std::to_string(spec.width) + "x" +
                                       std::to_string(spec.height));
  }
  image.data.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.data.data())) {
    throw InputError({path, 0, 0}, "cannot read the pixels: " + in->geterror());
  }
  return image;
}

}  // namespace arbor::imaging
