// What the commands share: CLI11 checks of option values, and the render overrides that
// `render`, `plan` and `export` take (one definition, one place that applies them).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "spec/scene_desc.h"

namespace arbor::app {

// A seed: a whole number from 0 to 2^64-1 (a larger one was once clamped silently, so different
// seeds gave the same tree).
CLI::Validator seed_check();
// A real number, finite and in [lo, hi], as strictly as the scene keys are checked (CLI11's
// Range lets NaN through).
CLI::Validator finite_in(double lo, double hi);
// An option that takes text: an empty value is refused (an empty --crop once rendered the whole
// image over the scene's outputs).
CLI::Validator non_empty();

// The scene settings the command line overrides; 0, empty or unset: the scene's.
struct RenderOverrides {
  int width = 0, height = 0, spp = 0;
  std::optional<std::uint64_t> seed;
  std::optional<spec::Integrator> integrator;
  std::optional<double> time;  // seconds of wind for every [[tree]]
  bool transparent = false;    // output.transparent_sky = true
  bool regularize = false;     // render.regularize = true
  bool lod = false;            // render.lod = true
};

// Which of the overrides a command offers (width, height and time always).
enum OverrideOptions : unsigned {
  kSppOption = 1u << 0,
  kSeedOption = 1u << 1,
  kIntegratorOption = 1u << 2,
  kTransparentOption = 1u << 3,
  kRegularizeOption = 1u << 4,
};

// Adds the overrides `which` names to `command`, bound to `o`; `spp_help` describes --spp.
void add_override_options(CLI::App* command, RenderOverrides& o, unsigned which,
                          const std::string& spp_help);

// Applies the overrides to a loaded scene. --spp sets the sample count of the integrator in use
// (the scene keeps one for each).
void apply_overrides(spec::SceneDesc& scene, const RenderOverrides& o);

// The overrides as `arbor render` options, to hand on to a work unit.
std::vector<std::string> override_arguments(const RenderOverrides& o);

}  // namespace arbor::app
