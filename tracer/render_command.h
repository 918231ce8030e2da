// `arbor render`: a scene file, with the command line's overrides, rendered to its outputs.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/scene_desc.h"

namespace arbor::trace {

struct RenderRequest {
  std::string scene;
  std::string exr, png, integrator;  // empty: the scene's
  int spp = 0, threads = 0, width = 0, height = 0;  // 0: the scene's (threads 0: all cores)
  std::optional<std::uint64_t> seed;
  std::optional<double> time;  // seconds of wind for every [[tree]]
  std::optional<int> frame;    // the [animation]'s frame N: clock N / fps, its seed, '#' in outputs
  bool force = false;          // render past the memory estimate
  bool resume = false;         // continue from the EXR's film state
  bool transparent = false;    // --transparent: output.transparent_sky = true
  double time_limit = 0;       // seconds; 0: none
  std::optional<double> checkpoint_seconds;  // overrides output.checkpoint_seconds
  std::string passes;          // "A:B": render passes A .. B-1 only; empty: all
  std::string crop;            // "X0,Y0,X1,Y1": render that window only; empty: all
  std::string ocio_config;     // the run's OCIO config (default_ocio_config())
};

// Whole numbers separated by `sep` ("0:8", "0,0,240,360"), `count` of them, each in [0, 2^31);
// InputError naming `option` and the expected `form` otherwise.
std::vector<int> parse_integers(const std::string& text, char sep, std::size_t count, const char* option,
                                const char* form);

// Applies `frame` (when given) to the scene: the clock, the frame's seed unless pinned, the
// frame number in place of the '#' run in every output path. InputError when the scene has no
// [animation], the frame is outside it, or an output names a frame number but no frame is given.
void apply_frame(SceneDesc& scene, std::optional<int> frame);

// Renders and writes; returns the exit status (0). InputError for bad input, RuntimeFailure when
// the work fails.
int render_command(const RenderRequest& request);

}  // namespace arbor::trace
