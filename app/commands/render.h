// `arbor render`: a scene file, with the command line's overrides, rendered to its outputs.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands/options.h"

namespace arbor::app {

struct RenderRequest {
  std::string scene;
  std::string exr, png;  // empty: the scene's
  RenderOverrides overrides;
  int threads = 0;           // 0: all cores
  std::optional<int> frame;  // the [animation]'s frame N: clock N / fps, its seed, '#' in outputs
  bool force = false;        // render past the memory estimate
  bool resume = false;       // continue from the EXR's film state
  double time_limit = 0;     // seconds; 0: none
  std::optional<double> checkpoint_seconds;  // overrides output.checkpoint_seconds
  std::string passes;                        // "A:B": render passes A .. B-1 only; empty: all
  std::string crop;                          // "X0,Y0,X1,Y1": render that window only; empty: all
  std::string ocio_config;                   // the run's OCIO config (default_ocio_config())
};

// Adds `arbor render` to `app`, its options bound to `request`.
CLI::App* add_render_command(CLI::App& app, RenderRequest& request);

// Renders and writes; returns the exit status (0, or 128 + N when signal N stopped it).
// InputError for bad input, RuntimeFailure when the work fails.
int render_command(const RenderRequest& request);

}  // namespace arbor::app
