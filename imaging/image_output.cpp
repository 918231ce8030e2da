// The image writers: EXR with AOVs and metadata, PNG through an OCIO display view.
#include "imaging/image_output.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <cmath>
#include <csetjmp>

#include <png.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>

#include "arbor/version.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/image_library.h"
#include "common/json.h"
#include "imaging/cryptomatte.h"

namespace arbor::imaging {

namespace {

// An OpenEXR output stream into memory: the file is encoded whole, then written by AtomicFile.
class MemoryStream final : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (pos_ + static_cast<std::uint64_t>(n) > bytes_.size())
      bytes_.resize(pos_ + static_cast<std::uint64_t>(n));
    std::memcpy(bytes_.data() + pos_, c, static_cast<std::size_t>(n));
    pos_ += static_cast<std::uint64_t>(n);
  }
  std::uint64_t tellp() override { return pos_; }
  void seekp(std::uint64_t pos) override { pos_ = pos; }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
  std::uint64_t pos_ = 0;
};

// One channel of the file: its name, type and a plane of the image's pixels.
struct Plane {
  std::string name;
  Imf::PixelType type;
  std::vector<float> values;
};

}  // namespace

namespace {

// The planes of an EXR, added in channel order: the colour, alpha and the asked-for AOVs.
class Planes {
 public:
  Planes(const Image& img, const OutputSpec& o)
      : img_(img),
        o_(o),
        n_(static_cast<std::size_t>(img.width) * img.height),
        colour_(o.pixel_type == PixelType::Float ? Imf::FLOAT : Imf::HALF) {}

  bool wants(Aov aov) const { return o_.aovs.has(aov); }
  Imf::PixelType colour() const { return colour_; }
  std::vector<Plane>& planes() { return planes_; }

  // Colour, alpha, albedo, normal, depth, variance, samples.
  void add_pixels() {
    triple("R", "G", "B", colour_, img_.beauty);
    // Alpha: the share of camera rays that hit something (RGB is premultiplied by it).
    plane("A", colour_) = img_.alpha.size() == n_ ? img_.alpha : std::vector<float>(n_, 1.0f);
    if (wants(Aov::Albedo)) triple("albedo.R", "albedo.G", "albedo.B", colour_, img_.albedo);
    if (wants(Aov::Normal)) triple("N.X", "N.Y", "N.Z", colour_, img_.normal);
    // Depth and variance keep full precision: reference tests divide by the variance.
    if (wants(Aov::Depth)) plane("Z", Imf::FLOAT) = img_.depth;
    if (wants(Aov::Variance))
      triple("variance.R", "variance.G", "variance.B", Imf::FLOAT, img_.variance);
    // Single-channel AOVs are PASS.X (Blender's multilayer reader drops a channel named without a
    // one-letter component, as it drops "object_id"; Nuke reads PASS as the layer).
    if (wants(Aov::Samples)) plane("samples.X", Imf::FLOAT) = img_.samples;
  }

  // object_id / material_id: the id that covers most of the pixel, as a float (exact to 2^24),
  // for a quick mask; Cryptomatte for anti-aliased mattes.
  void add_ids() {
    const bool ids = wants(Aov::ObjectId) || wants(Aov::MaterialId) || wants(Aov::CryptoObject) ||
                     wants(Aov::CryptoMaterial);
    if (ids && img_.id_slots == 0)
      throw std::logic_error("write_exr: id AOVs asked of an image without ids");
    if (wants(Aov::ObjectId)) top_id("object_id.X", img_.object_ids, img_.object_cover);
    if (wants(Aov::MaterialId)) top_id("material_id.X", img_.material_ids, img_.material_cover);
    if (wants(Aov::CryptoObject))
      crypto("crypto_object", img_.object_ids, img_.object_cover, img_.object_names);
    if (wants(Aov::CryptoMaterial))
      crypto("crypto_material", img_.material_ids, img_.material_cover, img_.material_names);
  }

  // The treemaker integrator's factors and contributions; they stay float: compare
  // --fit-treemaker solves with them.
  void add_treemaker() {
    if (!wants(Aov::Treemaker)) return;
    if (img_.extra_names.empty()) {
      // render_command refuses this scene (at its key) before rendering; reaching here is a bug.
      throw std::logic_error("write_exr: \"treemaker\" AOVs asked of an image without them");
    }
    const std::size_t e = img_.extra_names.size();
    for (std::size_t i = 0; i < e; ++i) {
      std::vector<float>& out = plane(img_.extra_names[i], Imf::FLOAT);
      for (std::size_t p = 0; p < n_; ++p) out[p] = img_.extra[p * e + i];
    }
  }

 private:
  std::vector<float>& plane(const std::string& name, Imf::PixelType type) {
    planes_.push_back({name, type, std::vector<float>(n_, 0.0f)});
    return planes_.back().values;
  }
  void triple(const char* a, const char* b, const char* c, Imf::PixelType type,
              const std::vector<glm::vec3>& v) {
    const char* names[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      std::vector<float>& out = plane(names[k], type);
      for (std::size_t p = 0; p < n_; ++p) out[p] = v[p][k];
    }
  }
  // Samples that hit nothing (the sky) count as id 0, which wins ties: a tree covering 40 % of a
  // sky pixel is not its object.
  void top_id(const char* name, const std::vector<std::uint32_t>& v,
              const std::vector<float>& cover) {
    const std::size_t slots = img_.id_slots;
    std::vector<float>& out = plane(name, Imf::FLOAT);
    for (std::size_t p = 0; p < n_; ++p) {
      float covered = 0.0f;
      for (std::size_t k = 0; k < slots; ++k) covered += cover[p * slots + k];
      const float nothing = 1.0f - covered;
      out[p] =
          v[p * slots] != 0 && cover[p * slots] > nothing ? static_cast<float>(v[p * slots]) : 0.0f;
    }
  }
  // Cryptomatte: ranks 0..5 in three RGBA channel sets (id, coverage, id, coverage).
  void crypto(const std::string& layer, const std::vector<std::uint32_t>& id,
              const std::vector<float>& cover, const std::vector<std::string>& names) {
    constexpr std::size_t kRanks = 6;
    const std::size_t slots = img_.id_slots;
    std::vector<float> hashed(names.size() + 1, 0.0f);
    for (std::size_t i = 0; i < names.size(); ++i) hashed[i + 1] = cryptomatte_id(names[i]);
    for (std::size_t set = 0; set < kRanks / 2; ++set) {
      char suffix[4];
      std::snprintf(suffix, sizeof suffix, "%02zu", set);
      const char* rgba[4] = {".R", ".G", ".B", ".A"};
      for (int c = 0; c < 4; ++c) {
        std::vector<float>& out = plane(layer + suffix + rgba[c], Imf::FLOAT);
        const std::size_t rank = 2 * set + static_cast<std::size_t>(c / 2);
        if (rank >= slots) continue;
        for (std::size_t p = 0; p < n_; ++p) {
          const std::uint32_t k = id[p * slots + rank];
          if (k == 0) continue;
          out[p] = c % 2 == 0 ? (k < hashed.size() ? hashed[k] : 0.0f) : cover[p * slots + rank];
        }
      }
    }
  }

  const Image& img_;
  const OutputSpec& o_;
  std::size_t n_;
  Imf::PixelType colour_;
  std::vector<Plane> planes_;
};

void text_attribute(Imf::Header& header, const std::string& key, const std::string& value) {
  header.insert(key, Imf::StringAttribute(value));
}
void int_attribute(Imf::Header& header, const char* key, int value) {
  header.insert(key, Imf::IntAttribute(value));
}

// The render's own attributes (arbor:…): how it was made, how far it got.
void add_render_attributes(Imf::Header& header, const Image& img, const OutputSpec& o,
                           const ExrMetadata& meta, bool variance) {
  auto text = [&](const char* key, const std::string& value) {
    text_attribute(header, key, value);
  };
  auto integer = [&](const char* key, int value) { int_attribute(header, key, value); };
  const int full_w = img.full_width > 0 ? img.full_width : img.width;
  const int full_h = img.full_height > 0 ? img.full_height : img.height;
  text("arbor:seed", std::to_string(meta.seed));
  integer("arbor:spp", meta.spp);
  text("arbor:integrator", meta.integrator);
  header.insert("arbor:render_seconds",
                Imf::FloatAttribute(static_cast<float>(meta.stats.seconds)));
  text("arbor:nonfinite_samples", std::to_string(meta.stats.nonfinite));
  // What the variance channels hold, only when there are some.
  if (variance)
    text("arbor:variance",
         meta.passes < 2 ? "variance of the pixel mean, sample variance / spp within one pass "
                           "(overstates it for QMC samples)"
         : meta.independent_passes
             ? "variance of the pixel mean, estimated across independent passes"
             : "variance of the pixel mean, estimated across passes of one "
               "sequence (an upper bound: the passes together are better "
               "stratified than independent ones)");
  integer("arbor:independent_passes", meta.independent_passes ? 1 : 0);
  integer("arbor:passes", meta.passes);
  integer("arbor:pass_spp", meta.pass_spp);
  integer("arbor:passes_planned", meta.passes_planned);
  text("arbor:pass_range", std::to_string(meta.pass_begin) + ":" + std::to_string(meta.pass_end));
  header.insert("arbor:mean_spp", Imf::FloatAttribute(static_cast<float>(meta.mean_spp)));
  text("arbor:fingerprint", meta.fingerprint);
  integer("arbor:transparent_sky", o.transparent_sky ? 1 : 0);
  text("arbor:regularize",
       meta.regularize ? "on: after the first bounce a glossy coat's GGX alpha < 0.3 becomes "
                         "clamp(2 alpha, 0.1, 0.3) (pbrt-v4's rule); biased, not a reference"
                       : "off");
  text("arbor:lod", meta.lod_quality > 0.0
                        ? "on, quality " + std::to_string(meta.lod_quality) +
                              ": trees thinned by range (Weber & Penn section 5); not a reference"
                        : std::string("off"));
  if (meta.noise_threshold > 0) {
    header.insert("arbor:noise_threshold",
                  Imf::FloatAttribute(static_cast<float>(meta.noise_threshold)));
    integer("arbor:min_spp", meta.min_spp);
  }
  if (img.width != full_w || img.height != full_h) {
    text("arbor:crop", std::to_string(img.x0) + "," + std::to_string(img.y0) + "," +
                           std::to_string(img.x0 + img.width) + "," +
                           std::to_string(img.y0 + img.height));
  }
  if (meta.incomplete) integer("arbor:incomplete", 1);
  if (!meta.stopped.empty()) text("arbor:stopped", meta.stopped);
  if (!meta.treemaker_weights.empty()) text("arbor:treemaker_weights", meta.treemaker_weights);
  if (!meta.exposure.empty()) text("arbor:exposure", meta.exposure);
}

// The colour space, stated as readers look for it: OIIO (and what is built on it) takes
// "oiio:ColorSpace" from the header; colorInteropID is the Color Interop Forum's id; the
// chromaticities are the EXR standard's own statement. An ACES container (SMPTE ST 2065-4) says
// so.
void add_colour_attributes(Imf::Header& header, const OutputSpec& o, const ExrMetadata& meta,
                           bool aces_container) {
  text_attribute(header, "oiio:ColorSpace", o.colorspace);
  text_attribute(header, "arbor:colorspace", o.colorspace);
  if (!meta.interop_id.empty()) text_attribute(header, "colorInteropID", meta.interop_id);
  const float* c = meta.chromaticities.size() == 8 ? meta.chromaticities.data() : nullptr;
  if (c) {
    header.insert("chromaticities", Imf::ChromaticitiesAttribute(Imf::Chromaticities(
                                        Imath::V2f(c[0], c[1]), Imath::V2f(c[2], c[3]),
                                        Imath::V2f(c[4], c[5]), Imath::V2f(c[6], c[7]))));
  }
  if (aces_container) {
    int_attribute(header, "acesImageContainerFlag", 1);
    header.insert("adoptedNeutral", Imf::V2fAttribute(Imath::V2f(c[6], c[7])));
  }
}

// The names of the numeric ids ({"name": id, …}) and the Cryptomatte layers' manifests.
void add_id_attributes(Imf::Header& header, const Image& img, const Planes& planes) {
  auto id_names = [&](const char* key, const std::vector<std::string>& names) {
    JsonObject ids_json;
    for (std::size_t i = 0; i < names.size(); ++i)
      ids_json.integer(names[i], static_cast<long long>(i + 1));
    text_attribute(header, key, ids_json.str());
  };
  if (planes.wants(Aov::ObjectId)) id_names("arbor:object_ids", img.object_names);
  if (planes.wants(Aov::MaterialId)) id_names("arbor:material_ids", img.material_names);
  auto crypto_header = [&](const std::string& layer, const std::vector<std::string>& names) {
    const std::string k = "cryptomatte/" + cryptomatte_key(layer) + "/";
    text_attribute(header, k + "name", layer);
    text_attribute(header, k + "hash", "MurmurHash3_32");
    text_attribute(header, k + "conversion", "uint32_to_float32");
    text_attribute(header, k + "manifest", cryptomatte_manifest(names));
  };
  if (planes.wants(Aov::CryptoObject)) crypto_header("crypto_object", img.object_names);
  if (planes.wants(Aov::CryptoMaterial)) crypto_header("crypto_material", img.material_names);
}

// The file encoded whole in memory.
void encode(const Image& img, const Imf::Header& header, std::vector<Plane>& planes,
            const Imath::Box2i& data, MemoryStream& memory) {
  Imf::OutputFile file(memory, header, 1);
  Imf::FrameBuffer frame;
  // OpenEXR writes a channel from a slice of its own type: half channels from half copies
  // (rounded to nearest, as Imath's conversion does).
  std::vector<std::vector<half>> halves;
  halves.reserve(planes.size());
  for (Plane& pl : planes) {
    const std::size_t row = static_cast<std::size_t>(img.width);
    if (pl.type == Imf::HALF) {
      halves.emplace_back(pl.values.begin(), pl.values.end());
      frame.insert(pl.name, Imf::Slice::Make(Imf::HALF, halves.back().data(), data, sizeof(half),
                                             sizeof(half) * row));
    } else {
      frame.insert(pl.name, Imf::Slice::Make(Imf::FLOAT, pl.values.data(), data, sizeof(float),
                                             sizeof(float) * row));
    }
  }
  file.setFrameBuffer(frame);
  file.writePixels(img.height);
}

}  // namespace

void write_exr(const Image& img, const OutputSpec& o, const ExrMetadata& meta,
               const std::string& path) {
  Planes planes(img, o);
  planes.add_pixels();
  planes.add_ids();
  planes.add_treemaker();
  const int full_w = img.full_width > 0 ? img.full_width : img.width;
  const int full_h = img.full_height > 0 ? img.full_height : img.height;
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(full_w - 1, full_h - 1));
  const Imath::Box2i data(Imath::V2i(img.x0, img.y0),
                          Imath::V2i(img.x0 + img.width - 1, img.y0 + img.height - 1));
  // An ACES container (SMPTE ST 2065-4) only when the file is one: ACES2065-1, half RGBA, no AOVs.
  const bool aces_container = meta.interop_id == "lin_ap0_scene" &&
                              meta.chromaticities.size() == 8 && planes.colour() == Imf::HALF &&
                              planes.planes().size() == 4;
  Imf::Header header(display, data, 1.0f, Imath::V2f(0.0f, 0.0f), 1.0f, Imf::INCREASING_Y,
                     aces_container ? Imf::PIZ_COMPRESSION : Imf::ZIP_COMPRESSION);
  for (const Plane& pl : planes.planes()) header.channels().insert(pl.name, Imf::Channel(pl.type));
  add_colour_attributes(header, o, meta, aces_container);
  text_attribute(header, "arbor:version", ARBOR_VERSION_STRING);
  text_attribute(header, "arbor:commit", ARBOR_COMMIT);
  text_attribute(header, "arbor:scene", meta.scene);
  if (meta.render_attributes)
    add_render_attributes(header, img, o, meta, planes.wants(Aov::Variance));
  add_id_attributes(header, img, planes);

  MemoryStream memory;
  try {
    encode(img, header, planes.planes(), data, memory);
  } catch (const std::exception& e) {
    throw RuntimeFailure("cannot write " + path + ": " + e.what());
  }
  AtomicFile out(path, true);
  out.write(memory.bytes().data(), memory.bytes().size());
  out.commit();
}

namespace {

// Whole-image PNG encoding into memory through libpng; libpng reports errors by longjmp, so no
// object with a destructor lives in this frame. "" or libpng's message.
struct PngSink {
  std::vector<unsigned char> bytes;
  char error[256] = "";
};

void png_append(png_structp png, png_bytep data, png_size_t n) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  sink->bytes.insert(sink->bytes.end(), data, data + n);
}
void png_flush(png_structp) {}
[[noreturn]] void png_fail(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->error, sizeof sink->error, "%s", message);
  png_longjmp(png, 1);
}
void png_warn(png_structp, png_const_charp) {}

bool encode_png(PngSink& sink, const unsigned char* rgb, int width, int height, png_bytep* rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_fail, png_warn);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &sink, png_append, png_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  for (int y = 0; y < height; ++y)
    rows[y] = const_cast<png_bytep>(rgb + static_cast<std::size_t>(y) * width * 3);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// A display-referred value in [0, 1] as 8 bits: rounded to nearest (ties to even), clamped —
// as OpenImageIO converts, so that PNGs kept their pixels when arbor stopped writing them
// through it.
unsigned char to_8_bit(float v) {
  const float s = v * 255.0f;
  if (!(s > 0.0f)) return 0;
  if (s >= 255.0f) return 255;
  return static_cast<unsigned char>(std::nearbyint(s));
}

}  // namespace

void write_png(const Image& img, const OutputSpec& o, const ColorPipeline& color,
               const std::string& path) {
  const ColorTransform shown = color.to_display(o.colorspace, o.display, o.view);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  std::vector<unsigned char> rgb(3 * n);
  for (std::size_t p = 0; p < n; ++p) {
    float v[3] = {img.beauty[p].x, img.beauty[p].y, img.beauty[p].z};
    shown(v);
    for (int c = 0; c < 3; ++c) rgb[3 * p + c] = to_8_bit(v[c]);
  }
  PngSink sink;
  std::vector<png_bytep> rows(static_cast<std::size_t>(img.height));
  if (!encode_png(sink, rgb.data(), img.width, img.height, rows.data()))
    throw RuntimeFailure("cannot write " + path + ": " + sink.error);
  AtomicFile file(path, true);
  file.write(sink.bytes.data(), sink.bytes.size());
  file.commit();
}

void write_encoded_atomic(const std::string& path, int width, int height, int channels,
                          const std::vector<float>& pixels, bool eight_bit) {
  std::vector<unsigned char> bytes;
  const std::string why = image_library("write " + path)
                              .encode(path, width, height, channels, pixels, eight_bit, bytes);
  if (!why.empty()) throw RuntimeFailure("cannot write " + path + ": " + why);
  AtomicFile file(path, true);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

std::string finished_exr_fingerprint(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const auto* incomplete = header.findTypedAttribute<Imf::IntAttribute>("arbor:incomplete");
    if (incomplete && incomplete->value() != 0) return "";
    const auto* fingerprint = header.findTypedAttribute<Imf::StringAttribute>("arbor:fingerprint");
    return fingerprint ? fingerprint->value() : "";
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace arbor::imaging
