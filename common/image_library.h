// Reading and encoding image files through OpenImageIO, which is loaded only when an image other
// than arbor's own EXR and PNG output is read or written (a texture, an environment map, the
// images `arbor compare` reads and draws). Debian's OpenImageIO pulls in 264 shared libraries;
// binding their symbols took 0.3–0.4 CPU-s at every start of every command, more than the rest
// of a cached render's start-up. The module libarbor_oiio.so (imaging/oiio_library.cpp) is
// dlopen'ed on first use; renders, farm units and growth never load it.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace arbor {

// The first subimage of a file: every channel, as floats, interleaved; with the file's metadata.
struct DecodedImage {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channel_names;
  // Per channel: 'h' half, 'f' float or double, 'i' integer (display-encoded: 8 or 16 bits).
  std::string channel_kinds;
  // Every attribute as text (numbers as OIIO prints them), e.g. "oiio:ColorSpace" = "sRGB".
  std::map<std::string, std::string> attributes;
  std::vector<float> pixels;  // width*height*channels; empty when only the header was read

  std::string attribute(const std::string& name, const std::string& fallback = "") const;
  int int_attribute(const std::string& name, int fallback) const;
};

// What the module offers. Every call reports failure as a non-empty message, never by throwing:
// no exception crosses the module's boundary.
class ImageLibrary {
 public:
  virtual ~ImageLibrary() = default;
  // The file's first subimage; its pixels only when `pixels`. A failure's message completes
  // "cannot read the image: …" (OIIO's reason, "its pixels: …", "it has an unsupported size …").
  virtual std::string read(const std::string& path, bool pixels, DecodedImage& out) const = 0;
  // The bytes of `pixels` (width*height*channels floats in [0, 1] written as 8 bits, or as
  // floats when !eight_bit) in the format `path`'s extension names.
  virtual std::string encode(const std::string& path, int width, int height, int channels,
                             const std::vector<float>& pixels, bool eight_bit,
                             std::vector<unsigned char>& bytes) const = 0;
  // Whether some format writes files with `path`'s extension.
  virtual bool writable(const std::string& path) const = 0;
  // Colour conversion of an image's pixels in place through the OCIO config: a colour space to
  // another (`display` empty; an alpha channel, by its name, unpremultiplied around it), or a
  // colour space to a display's view (`display` and `view` set; `to` unused).
  virtual std::string convert(DecodedImage& image, const std::string& config,
                              const std::string& from, const std::string& to,
                              const std::string& display, const std::string& view) const = 0;
  // Draws `text` in white on an RGB float picture, its baseline at y, starting at x (or ending
  // there when right_aligned). Without FreeType or the font nothing is drawn: labels are a
  // convenience.
  virtual void draw_text(std::vector<float>& rgb, int width, int height, int x, int y,
                         const std::string& text, int size, bool right_aligned) const = 0;
};

// The module, loaded on the first call: beside the executable in ../lib/arbor/ (the build tree
// has the installed layout), else where the build put it. RuntimeFailure naming the module and
// what needed it when it cannot be loaded.
const ImageLibrary& image_library(const std::string& needed_for);

// The file's first subimage (its pixels only when `pixels`) through image_library(). InputError
// naming the file when it is not a readable regular file (`what` says what it should be: "image",
// "environment map") or cannot be decoded.
DecodedImage read_image_file(const std::string& path, const std::string& what, bool pixels);

}  // namespace arbor
