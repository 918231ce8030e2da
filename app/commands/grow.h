// `arbor grow`: a species file to a tree, its statistics and its exports.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace arbor::app {

struct GrowRequest {
  std::string species;
  std::uint64_t seed = 1;
  double time = 0.0;
  double quality = 1.0;
  std::string out;       // .obj, .ply, .pbrt or .skel; empty: none
  std::string up = "z";  // "z" or "y": the up axis of the .obj, .ply or .pbrt written
  bool stats = false;    // print the statistics as text
  bool json = false;     // print them as one JSON object
  bool force = false;    // grow even past the size limits
};

// Adds `arbor grow` to `app`, its options bound to `request`.
CLI::App* add_grow_command(CLI::App& app, GrowRequest& request);

// Grows and writes; returns the exit status (0). InputError for bad input, RuntimeFailure when
// the work fails.
int grow_command(const GrowRequest& request);

}  // namespace arbor::app
