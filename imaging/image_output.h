// Image files of a render: EXR with AOVs, variance and metadata; PNG through a display view.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imaging/output_spec.h"
#include "imaging/color.h"
#include "imaging/image.h"

namespace arbor::imaging {

struct ExrMetadata {
  std::string scene;
  std::uint64_t seed = 0;
  int spp = 0;
  std::string integrator;
  RenderStats stats;
  // The treemaker integrator's weights as "ambient=… lambert=… height=… radius=… angle=…" when
  // every tree shares them, "per tree" when they differ; empty for the path integrator.
  std::string treemaker_weights;
  std::string exposure;      // arbor:exposure: the stops the pixels carry (empty: not written)
  bool regularize = false;   // arbor:regularize: the path integrator's regularisation
  double lod_quality = 0.0;  // arbor:lod: level of detail's quality factor; 0: off
  // The passes (docs/rendering.md, "Passes"): pass_spp samples each, passes_planned in all;
  // this image holds passes [pass_begin, pass_begin + passes).
  int pass_spp = 0, passes = 1, passes_planned = 1, pass_begin = 0, pass_end = 1;
  bool independent_passes = false;  // each pass its own scramble (else one sequence)
  bool incomplete = false;          // stopped by a signal before the passes asked for
  std::string stopped;              // "", "interrupted" or "time limit"
  std::string fingerprint;          // of the scene, its inputs and the settings (film_file.h)
  double noise_threshold = 0.0;
  int min_spp = 0;
  double mean_spp = 0.0;  // samples a pixel on average (below spp with adaptive sampling)
  // The output colour space's chromaticities (ColorPipeline::chromaticities: 8 floats, or empty)
  // and Color Interop Forum id ("" when arbor does not know the space).
  std::vector<float> chromaticities;
  std::string interop_id;
  // false for an image that is not a render (the sky exported for pbrt): no arbor:spp, seed,
  // passes and the like, only the version, the scene note and the colour tags.
  bool render_attributes = true;
};

// Writes the EXR atomically (a temporary beside it, renamed when complete). Channels: R G B,
// then the requested AOVs: albedo.{R,G,B}, N.{X,Y,Z}, Z, variance.{R,G,B}, samples, and for
// "treemaker" the image's extra channels (float). A crop is written as its data window within
// the whole image's display window. "treemaker" must only be asked of an image that has them
// (the treemaker integrator's; std::logic_error otherwise).
void write_exr(const Image& image, const OutputSpec& output, const ExrMetadata& meta,
               const std::string& path);

// Writes an 8-bit PNG of the beauty through the output's display and view, atomically.
void write_png(const Image& image, const OutputSpec& output, const ColorPipeline& color,
               const std::string& path);

// Encodes pixels (width*height*channels floats; display-referred in [0, 1] when eight_bit) in the
// format path's extension names, through OpenImageIO (libarbor_oiio.so), and writes the file
// atomically. RuntimeFailure naming the file when it cannot.
void write_encoded_atomic(const std::string& path, int width, int height, int channels,
                          const std::vector<float>& pixels, bool eight_bit);

// The arbor:fingerprint of an EXR that is a finished render; "" when it cannot be read as an EXR,
// has none, or says it is incomplete.
std::string finished_exr_fingerprint(const std::string& path);

}  // namespace arbor::imaging
