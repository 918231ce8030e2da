// Internal to tracer/: writes an OIIO image buffer atomically (a temporary beside the target,
// renamed over it when complete; the format follows the extension); reads every channel of an
// image for the comparison tools.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

namespace arbor::imaging {

// Encodes an image (the format by the extension of `path`) and writes it atomically through
// AtomicFile: write_pixels writes the pixels to the opened output and says whether it could.
void write_image_atomic(const std::string& path, const OIIO::ImageSpec& spec,
                        const std::function<bool(OIIO::ImageOutput&)>& write_pixels);
void write_imagebuf_atomic(const OIIO::ImageBuf& buf, const std::string& path, OIIO::TypeDesc type);

// Every channel of an image's first subimage as floats, interleaved.
struct ImageChannels {
  std::string path;
  OIIO::ImageSpec spec;
  std::vector<float> data;  // width*height*nchannels
  // The channel called `name`, or -1. (EXR keeps channels by name; readers reorder them.)
  int index(const std::string& name) const;
  // The value of channel c at pixel p; InputError naming the file and pixel when it is not finite.
  float finite(std::size_t p, int c, const char* what) const;
};

// InputError (naming the file) when it cannot be read or has an unsupported size.
ImageChannels read_image_channels(const std::string& path);

}  // namespace arbor::imaging
