// Colour management and image files: OpenColorIO through OpenImageIO, arbor's own config.ocio
// unless $OCIO names another, EXR with AOVs, variance and metadata, PNG through a display view.
#pragma once

#include <memory>
#include <string>

#include "tracer/film.h"
#include "tracer/scene_desc.h"

namespace arbor::trace {

class ColorPipeline {
 public:
  // Loads the config and checks the output's colour space, display and view exist in it
  // (InputError listing what does otherwise).
  explicit ColorPipeline(const OutputDesc& output);
  ~ColorPipeline();
  ColorPipeline(const ColorPipeline&) = delete;
  ColorPipeline& operator=(const ColorPipeline&) = delete;

  const std::string& config_path() const { return config_path_; }
  // scene_linear → the output colour space, per pixel, thread-safe.
  ColorTransform to_output() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string config_path_;
};

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
// the image's extra channels (float). Throws InputError when "treemaker" is asked of an image
// that has none (rendered by the path integrator).
void write_exr(const Image& image, const OutputDesc& output, const ExrMetadata& meta,
               const std::string& path);

// Writes an 8-bit PNG of the beauty through the output's display and view, atomically.
void write_png(const Image& image, const OutputDesc& output, const ColorPipeline& color,
               const std::string& path);

// The config arbor uses: $OCIO when set, else the config.ocio shipped with arbor.
std::string ocio_config_path();

}  // namespace arbor::trace
