// Size and shape statistics of a grown tree (what `arbor grow --stats` prints).
#pragma once

#include <string>
#include <vector>

#include "generator/skeleton.h"

namespace arbor::gen {

struct TreeStats {
  std::vector<long long> stems_per_level;  // stems including clones, by level
  long long leaves = 0;
  long long curve_segments = 0;  // limb segments between consecutive skeleton points
  long long triangles = 0;       // leaf triangles (limbs render as curves, not triangles)
  long long points = 0;
  double height = 0.0;       // metres: highest point of any limb or leaf above the ground
  double crown_width = 0.0;  // metres: twice the largest horizontal distance from the trunk axis
  double seconds = 0.0;      // time spent growing

  long long stems() const;   // all levels, clones included
};

TreeStats compute_stats(const Skeleton& skeleton);

// One JSON object with the contract's keys (and a few more), for `--stats --json`.
std::string stats_json(const TreeStats& stats, const std::string& species, unsigned long long seed,
                       long long mesh_triangles);
// Human-readable lines for `--stats`.
std::string stats_text(const TreeStats& stats);

}  // namespace arbor::gen
