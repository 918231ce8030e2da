// Image files of a render: EXR with AOVs, variance and metadata; PNG through a display view.
#pragma once

#include <cstdint>
#include <string>

#include "formats/scene_desc.h"
#include "imaging/color.h"
#include "imaging/image.h"

namespace arbor::trace {

struct ExrMetadata {
  std::string scene;
  std::uint64_t seed = 0;
  int spp = 0;
  std::string integrator;
  RenderStats stats;
  // The treemaker integrator's weights as "ambient=… lambert=… height=… radius=… angle=…" when
  // every tree shares them, "per tree" when they differ; empty for the path integrator.
  std::string treemaker_weights;
};

// Writes the EXR atomically (a temporary beside it, renamed when complete). Channels: R G B,
// then the requested AOVs: albedo.{R,G,B}, N.{X,Y,Z}, Z, variance.{R,G,B}, and for "treemaker"
// the image's extra channels (float). "treemaker" must only be asked of an image that has them
// (the treemaker integrator's; std::logic_error otherwise).
void write_exr(const Image& image, const OutputDesc& output, const ExrMetadata& meta,
               const std::string& path);

// Writes an 8-bit PNG of the beauty through the output's display and view, atomically.
void write_png(const Image& image, const OutputDesc& output, const ColorPipeline& color,
               const std::string& path);

}  // namespace arbor::trace
