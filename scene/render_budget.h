// The memory a render will need, estimated from the scene before anything is allocated, so that
// an absurd image size or forest is refused up front instead of exhausting the machine.
#pragma once

#include <cstddef>
#include <cstdint>

#include "spec/scene_desc.h"

namespace arbor::scene {

// What the film keeps a pixel, in bytes: the tracer's Film states it (film_costs() in
// tracer/film.h), the estimate does not copy it.
struct FilmCosts {
  std::uint64_t state = 0;             // a pixel's running state
  std::uint64_t sum = 8;               // each value it sums
  std::uint64_t sums = 0;              // the values every pixel sums (colour, alpha, AOVs)
  std::uint64_t id_sums = 0;           // more values when the compositing ids are kept
  std::uint64_t record_extra = 0;      // a pass record holds the sums and this many values more
  std::uint64_t treemaker_extras = 0;  // the treemaker AOVs' values
};

// One placed tree: its Embree instance, placement and materials (calibrated, see below). A
// community's plants are known only once simulated: the estimate counts trees and forests, and
// `arbor inspect` multiplies this by the instances built.
constexpr std::uint64_t kBytesPerInstance = 1024;

struct MemoryEstimate {
  std::uint64_t image_bytes = 0;     // the film, its AOVs and the encoded outputs
  std::uint64_t instance_bytes = 0;  // kBytesPerInstance per tree and forest instance
  std::uint64_t instances = 0;
  std::uint64_t meadow_bytes = 0;   // the meadow's distinct blades and its tiles' instances
  std::uint64_t terrain_bytes = 0;  // the terrain's vertices and Embree's grid over them
  std::uint64_t total() const {
    return image_bytes + instance_bytes + meadow_bytes + terrain_bytes;
  }
};

// Calibrated on the development machine (peak RSS of renders at growing sizes, /usr/bin/time):
// about 77 bytes a pixel with beauty only, 106 with four AOVs, 257 with the treemaker AOVs, and 0.7
// KB a forest instance, before the film kept its state across passes (144 bytes a pixel more, 8 a
// treemaker AOV; a work unit of passes A:B with A > 0 also keeps each pass: `record_passes` of
// 112 bytes a pixel). Measured since: a 2000x2000 render peaks at 996 MB with beauty only (about
// 225 bytes a pixel over the baseline) and 1043 MB with the variance AOV; the estimate (240 and
// 264) rounds each up. Tree geometry is not included: each tree has
// its own size limit when it is grown.
MemoryEstimate estimate_render_memory(const spec::SceneDesc& scene, const FilmCosts& film,
                                      std::uint64_t record_passes = 0);

// What this process may use: the machine's physical memory, or the address-space or data-size
// limit (ulimit -v / -d) when it is lower.
std::uint64_t usable_memory_bytes();

// InputError (at the largest forest, or the scene file) when the estimate exceeds `usable`
// bytes, saying how much each part needs and that --force renders it anyway.
void check_render_memory(const spec::SceneDesc& scene, const FilmCosts& film, bool force,
                         std::uint64_t usable = usable_memory_bytes(),
                         std::uint64_t record_passes = 0);

// The bytes left for tree geometry once the image, the instances and the libraries have theirs
// (0 with `force`: no limit). build_scene refuses a forest whose variants would not fit.
std::uint64_t geometry_budget(const spec::SceneDesc& scene, const FilmCosts& film, bool force,
                              std::uint64_t usable = usable_memory_bytes(),
                              std::uint64_t record_passes = 0);

// Refuses a forest whose variants would not fit `budget` bytes (0: no budget), from the scene's
// geometry bytes before and after its first variant. Every variant of a species is about the
// size of its first (the Weber & Penn size limits allow a 10^4 spread, but variants differ only by
// their seed); Embree's structures double it.
void check_forest_budget(const spec::ForestDesc& forest, std::size_t before, std::size_t after,
                         std::uint64_t budget);

}  // namespace arbor::scene
