// Colour management: one OpenColorIO config per run, the conversions the renderer needs from it,
// and where arbor finds its config.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "formats/scene_desc.h"

namespace arbor::trace {

// Converts a colour in place (thread-safe).
using ColorTransform = std::function<void(float rgb[3])>;

class ColorPipeline {
 public:
  // Loads the config; InputError naming the file when OCIO cannot use it.
  explicit ColorPipeline(std::string config_path);
  ~ColorPipeline();
  ColorPipeline(const ColorPipeline&) = delete;
  ColorPipeline& operator=(const ColorPipeline&) = delete;

  const std::string& config_path() const { return config_path_; }

  // InputError at the scene key when the output's colour space, display or view is not in the
  // config, listing what the config has.
  void check(const OutputDesc& output) const;
  // scene_linear → `colorspace`, per pixel.
  ColorTransform to_output(const std::string& colorspace) const;
  // CIE XYZ (D65) → scene_linear, for the sky models; the config must define
  // "Linear CIE-XYZ-D65" (InputError otherwise).
  ColorTransform xyz_to_scene_linear() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string config_path_;
};

// The config a run of arbor uses: $OCIO when it is set and not empty, else the config.ocio
// installed with the executable (`<prefix>/share/arbor/ocio/config.ocio` for `<prefix>/bin/arbor`;
// the build tree has the same layout). Read once, by the program, and passed on.
std::string default_ocio_config();

}  // namespace arbor::trace
