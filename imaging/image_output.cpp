// The image writers: EXR with AOVs and metadata, PNG through an OCIO display view.
#include "imaging/image_output.h"

#include <cstdio>
#include <stdexcept>

#include <OpenImageIO/color.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "arbor/version.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "imaging/image_file.h"

namespace arbor::trace {

void write_exr(const Image& img, const OutputDesc& o, const ExrMetadata& meta,
               const std::string& path) {
  std::vector<std::string> names{"R", "G", "B"};
  std::vector<OIIO::TypeDesc> formats(3, o.pixel_type == "float" ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF);
  auto wants = [&](const char* aov) {
    for (const std::string& a : o.aovs) {
      if (a == aov) return true;
    }
    return false;
  };
  const bool albedo = wants("albedo"), normal = wants("normal"), depth = wants("depth"),
             variance = wants("variance");
  if (albedo) for (const char* c : {"albedo.R", "albedo.G", "albedo.B"}) { names.emplace_back(c); formats.push_back(formats[0]); }
  if (normal) for (const char* c : {"N.X", "N.Y", "N.Z"}) { names.emplace_back(c); formats.push_back(formats[0]); }
  // Depth and variance keep full precision: reference tests divide by the variance.
  if (depth) { names.emplace_back("Z"); formats.push_back(OIIO::TypeDesc::FLOAT); }
  if (variance) for (const char* c : {"variance.R", "variance.G", "variance.B"}) { names.emplace_back(c); formats.push_back(OIIO::TypeDesc::FLOAT); }
  const bool samples = wants("samples");
  if (samples) { names.emplace_back("samples"); formats.push_back(OIIO::TypeDesc::FLOAT); }
  const bool treemaker = wants("treemaker");
  if (treemaker && img.extra_names.empty()) {
    // render_command refuses this scene (at its key) before rendering; reaching here is a bug.
    throw std::logic_error("write_exr: \"treemaker\" AOVs asked of an image without them");
  }
  // The factors and contributions stay float: compare --fit-treemaker solves with them.
  if (treemaker) for (const std::string& c : img.extra_names) { names.push_back(c); formats.push_back(OIIO::TypeDesc::FLOAT); }

  const int nch = static_cast<int>(names.size());
  OIIO::ImageSpec spec(img.width, img.height, nch, formats[0]);
  spec.channelnames = names;
  spec.channelformats = formats;
  spec.x = img.x0;
  spec.y = img.y0;
  spec.full_x = spec.full_y = 0;
  spec.full_width = img.full_width > 0 ? img.full_width : img.width;
  spec.full_height = img.full_height > 0 ? img.full_height : img.height;
  spec.attribute("oiio:ColorSpace", o.colorspace);
  spec.attribute("arbor:colorspace", o.colorspace);
  spec.attribute("arbor:version", ARBOR_VERSION_STRING);
  spec.attribute("arbor:commit", ARBOR_COMMIT);
  spec.attribute("arbor:scene", meta.scene);
  spec.attribute("arbor:seed", std::to_string(meta.seed));
  spec.attribute("arbor:spp", meta.spp);
  spec.attribute("arbor:integrator", meta.integrator);
  spec.attribute("arbor:render_seconds", static_cast<float>(meta.stats.seconds));
  spec.attribute("arbor:nonfinite_samples", std::to_string(meta.stats.nonfinite));
  // What the variance channels hold, only when there are some.
  if (variance) spec.attribute("arbor:variance",
                 meta.passes < 2 ? "variance of the pixel mean, sample variance / spp within one pass "
                                   "(overstates it for QMC samples)"
                 : meta.independent_passes ? "variance of the pixel mean, estimated across independent passes"
                                           : "variance of the pixel mean, estimated across passes of one "
                                             "sequence (an upper bound: the passes together are better "
                                             "stratified than independent ones)");
  spec.attribute("arbor:independent_passes", meta.independent_passes ? 1 : 0);
  spec.attribute("arbor:passes", meta.passes);
  spec.attribute("arbor:pass_spp", meta.pass_spp);
  spec.attribute("arbor:passes_planned", meta.passes_planned);
  spec.attribute("arbor:pass_range", std::to_string(meta.pass_begin) + ":" + std::to_string(meta.pass_end));
  spec.attribute("arbor:mean_spp", static_cast<float>(meta.mean_spp));
  spec.attribute("arbor:fingerprint", meta.fingerprint);
  if (meta.noise_threshold > 0) {
    spec.attribute("arbor:noise_threshold", static_cast<float>(meta.noise_threshold));
    spec.attribute("arbor:min_spp", meta.min_spp);
  }
  if (img.width != spec.full_width || img.height != spec.full_height) {
    spec.attribute("arbor:crop", std::to_string(img.x0) + "," + std::to_string(img.y0) + "," +
                                     std::to_string(img.x0 + img.width) + "," + std::to_string(img.y0 + img.height));
  }
  if (meta.incomplete) spec.attribute("arbor:incomplete", 1);
  if (!meta.stopped.empty()) spec.attribute("arbor:stopped", meta.stopped);
  if (!meta.treemaker_weights.empty()) spec.attribute("arbor:treemaker_weights", meta.treemaker_weights);
  spec.attribute("compression", "zip");
  // The EXR standard's own statement of the colour space, for the spaces arbor's config defines.
  const struct { const char* name; float c[8]; } primaries[] = {
      {"ACEScg", {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f}},
      {"ACES2065-1", {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}},
      {"Linear Rec.709 (sRGB)", {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}},
  };
  for (const auto& p : primaries) {
    if (o.colorspace == p.name) {
      spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), p.c);
    }
  }

  std::vector<float> data(static_cast<std::size_t>(img.width) * img.height * nch);
  for (std::size_t p = 0, k = 0; p < img.beauty.size(); ++p) {
    auto put = [&](const glm::vec3& v) { data[k++] = v.x; data[k++] = v.y; data[k++] = v.z; };
    put(img.beauty[p]);
    if (albedo) put(img.albedo[p]);
    if (normal) put(img.normal[p]);
    if (depth) data[k++] = img.depth[p];
    if (variance) put(img.variance[p]);
    if (samples) data[k++] = img.samples[p];
    if (treemaker) {
      const std::size_t e = img.extra_names.size();
      for (std::size_t i = 0; i < e; ++i) data[k++] = img.extra[p * e + i];
    }
  }
  write_image_atomic(path, spec, [&](OIIO::ImageOutput& out) {
    return out.write_image(OIIO::TypeDesc::FLOAT, data.data());
  });
}

void write_png(const Image& img, const OutputDesc& o, const ColorPipeline& color,
               const std::string& path) {
  OIIO::ImageBuf src(OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const glm::vec3& v = img.beauty[static_cast<std::size_t>(y) * img.width + x];
      const float px[3] = {v.x, v.y, v.z};
      src.setpixel(x, y, px);
    }
  }
  OIIO::ColorConfig config(color.config_path());
  OIIO::ImageBuf shown;
  if (!OIIO::ImageBufAlgo::ociodisplay(shown, src, o.display, o.view, o.colorspace, "", false, "",
                                        "", &config)) {
    throw RuntimeFailure("cannot apply the display view for " + path + ": " + shown.geterror());
  }
  write_imagebuf_atomic(shown, path, OIIO::TypeDesc::UINT8);
}

void write_image_atomic(const std::string& path, const OIIO::ImageSpec& spec,
                        const std::function<bool(OIIO::ImageOutput&)>& write_pixels) {
  // OIIO's writers do not all report a failed write (a PNG on a full disk "succeeds"), so the
  // file is encoded in memory and written by AtomicFile, which checks every byte reaches disk.
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw RuntimeFailure("cannot write " + path + ": " + OIIO::geterror());
  OIIO::ImageSpec with_proxy = spec;
  void* proxy = &memory;
  with_proxy.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out->open(path, with_proxy) || !write_pixels(*out) || !out->close()) {
    throw RuntimeFailure("cannot write " + path + ": " + out->geterror());
  }
  AtomicFile file(path, true);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

void write_imagebuf_atomic(const OIIO::ImageBuf& buf, const std::string& path, OIIO::TypeDesc type) {
  OIIO::ImageSpec spec = buf.spec();
  spec.set_format(type);
  write_image_atomic(path, spec, [&](OIIO::ImageOutput& out) { return buf.write(&out); });
}

}  // namespace arbor::trace
