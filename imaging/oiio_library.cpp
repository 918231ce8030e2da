// libarbor_oiio.so: the ImageLibrary of common/image_library.h, through OpenImageIO. Built as a
// module of its own and dlopen'ed on first use, so that only the commands that read or draw
// images through OpenImageIO pay for loading it.
#include <exception>
#include <string>

#include <OpenImageIO/color.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "common/image_library.h"

namespace arbor::imaging {

namespace {

// By name: OIIO looks for it in its font folders ($OPENIMAGEIO_FONTS, the system's fonts).
const char* const kFont = "DejaVuSans";

std::string text_of(const OIIO::ParamValue& p) {
  if (p.type() == OIIO::TypeDesc::STRING) return p.get_string();
  if (p.type() == OIIO::TypeDesc::INT) return std::to_string(p.get_int());
  return p.get_string();
}

char kind_of(OIIO::TypeDesc t) {
  if (t == OIIO::TypeDesc::HALF) return 'h';
  return t.is_floating_point() ? 'f' : 'i';
}

// A float ImageBuf over `pixels` (not a copy), its channels named as the image's.
OIIO::ImageBuf wrap(const DecodedImage& image, std::vector<float>& pixels) {
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  if (static_cast<int>(image.channel_names.size()) == image.channels) {
    spec.channelnames = image.channel_names;
    spec.alpha_channel = -1;
    for (int c = 0; c < image.channels; ++c) {
      const std::string& n = image.channel_names[static_cast<std::size_t>(c)];
      if (n == "A" || n == "a" || n == "Alpha") spec.alpha_channel = c;
    }
  }
  return OIIO::ImageBuf(spec, pixels.data());
}

class OiioLibrary final : public ImageLibrary {
 public:
  std::string read(const std::string& path, bool pixels, DecodedImage& out) const override {
    try {
      auto in = OIIO::ImageInput::open(path);
      if (!in) {
        std::string why = OIIO::geterror();
        return why.empty() ? "it cannot be read as an image" : why;
      }
      const OIIO::ImageSpec& spec = in->spec();
      const long long n = static_cast<long long>(spec.width) * spec.height;
      if (spec.width <= 0 || spec.height <= 0 || n > (1LL << 28) || spec.nchannels < 1 ||
          spec.nchannels > 1024 || n * spec.nchannels > (1LL << 30)) {
        return "it has an unsupported size " + std::to_string(spec.width) + "x" +
               std::to_string(spec.height) + " with " + std::to_string(spec.nchannels) +
               " channels";
      }
      out.width = spec.width;
      out.height = spec.height;
      out.channels = spec.nchannels;
      out.channel_names = spec.channelnames;
      out.channel_kinds.clear();
      for (int c = 0; c < spec.nchannels; ++c) out.channel_kinds += kind_of(spec.channelformat(c));
      out.attributes.clear();
      for (const OIIO::ParamValue& p : spec.extra_attribs)
        out.attributes[p.name().string()] = text_of(p);
      out.pixels.clear();
      if (!pixels) return {};
      out.pixels.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(spec.nchannels));
      if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data()))
        return "its pixels: " + in->geterror();
      return {};
    } catch (const std::exception& e) {
      return e.what();
    }
  }

  std::string encode(const std::string& path, int width, int height, int channels,
                     const std::vector<float>& pixels, bool eight_bit,
                     std::vector<unsigned char>& bytes) const override {
    try {
      // OIIO's writers do not all report a failed write (a PNG on a full disk "succeeds"), so
      // the file is encoded in memory; the caller writes it and checks every byte reaches disk.
      bytes.clear();
      OIIO::Filesystem::IOVecOutput memory(bytes);
      auto out = OIIO::ImageOutput::create(path);
      if (!out) return OIIO::geterror();
      OIIO::ImageSpec spec(width, height, channels,
                           eight_bit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
      void* proxy = &memory;
      spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
      if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
          !out->close())
        return out->geterror();
      return {};
    } catch (const std::exception& e) {
      return e.what();
    }
  }

  bool writable(const std::string& path) const override {
    return static_cast<bool>(OIIO::ImageOutput::create(path));
  }

  std::string convert(DecodedImage& image, const std::string& config, const std::string& from,
                      const std::string& to, const std::string& display,
                      const std::string& view) const override {
    try {
      OIIO::ImageBuf src = wrap(image, image.pixels);
      OIIO::ColorConfig colour(config);
      OIIO::ImageBuf dst;
      const bool ok =
          display.empty()
              ? OIIO::ImageBufAlgo::colorconvert(dst, src, from, to, true, "", "", &colour)
              : OIIO::ImageBufAlgo::ociodisplay(dst, src, display, view, from, "", false, "", "",
                                                &colour);
      if (!ok) return dst.geterror();
      if (!dst.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data()))
        return dst.geterror();
      return {};
    } catch (const std::exception& e) {
      return e.what();
    }
  }

  void draw_text(std::vector<float>& rgb, int width, int height, int x, int y,
                 const std::string& text, int size, bool right_aligned) const override {
    try {
      OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), rgb.data());
      const float white[3] = {1.0f, 1.0f, 1.0f};
      OIIO::ImageBufAlgo::render_text(buf, x, y, text, size, kFont, white,
                                      right_aligned ? OIIO::ImageBufAlgo::TextAlignX::Right
                                                    : OIIO::ImageBufAlgo::TextAlignX::Left);
      (void)buf.geterror();  // a missing font is not an error: the picture is drawn without it
    } catch (const std::exception&) {
    }
  }
};

}  // namespace

}  // namespace arbor::imaging

extern "C" __attribute__((visibility("default"))) const arbor::ImageLibrary* arbor_image_library() {
  static const arbor::imaging::OiioLibrary library;
  return &library;
}
