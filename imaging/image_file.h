// Reads every channel of an image (through OpenImageIO, libarbor_oiio.so) for the comparison
// tools.
#pragma once

#include <string>
#include <vector>

#include "common/image_library.h"

namespace arbor::imaging {

// Every channel of an image's first subimage as floats, interleaved (image.pixels).
struct ImageChannels {
  std::string path;
  DecodedImage image;
  // The channel called `name`, or -1. (EXR keeps channels by name; readers reorder them.)
  int index(const std::string& name) const;
  // The value of channel c at pixel p; InputError naming the file and pixel when it is not finite.
  float finite(std::size_t p, int c, const char* what) const;
};

// InputError (naming the file) when it cannot be read or has an unsupported size.
ImageChannels read_image_channels(const std::string& path);

}  // namespace arbor::imaging
