// `arbor export`: a scene file written as a complete pbrt-v4 scene (tracer/pbrt_scene.h).
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands/options.h"

namespace arbor::app {

struct ExportRequest {
  std::string scene;
  std::string out;            // OUT.pbrt; the sky goes beside it as OUT.sky.exr
  RenderOverrides overrides;  // width, height, spp (pbrt's pixel samples), time
  std::optional<int> frame;   // the [animation]'s frame N (its clock and seed)
  int sky_resolution = 512;   // texels along each side of the sky's equal-area square
  std::string ocio_config;    // the run's OCIO config (default_ocio_config())
};

// Adds `arbor export` to `app`, its options bound to `request`.
CLI::App* add_export_command(CLI::App& app, ExportRequest& request);

// Writes OUT.pbrt and its sky; returns the exit status (0). InputError for bad input,
// RuntimeFailure when the work fails. Every file is written atomically.
int export_command(const ExportRequest& request);

}  // namespace arbor::app
