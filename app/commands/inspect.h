// `arbor inspect`: what a scene builds, without rendering it — every tree instance (species,
// prototype, variant, position, rotation, scale, age), the terrain under each, counts per species
// and size class, the meadow's blades, the rocks and the memory estimate (docs/landscape.md).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace arbor::app {

struct InspectRequest {
  std::string scene;
  bool json = false;       // everything as one JSON object on stdout
  bool instances = false;  // the text report lists every instance too, one a line
  std::string ocio_config;
};

// Adds `arbor inspect` to `app`, its options bound to `request`.
CLI::App* add_inspect_command(CLI::App& app, InspectRequest& request);

// Builds the scene and reports it on stdout; returns the exit status (0). InputError for bad
// input (nothing is written anywhere).
int inspect_command(const InspectRequest& request);

}  // namespace arbor::app
