// Size and shape statistics of a grown tree (what `arbor grow --stats` prints).
#pragma once

#include <string>
#include <vector>

#include "generator/skeleton.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::generator {

struct TreeStats {
  std::vector<long long> stems_per_level;  // stems including clones, by level
  long long leaves = 0;
  long long skeleton_segments = 0;  // limb segments between consecutive skeleton points
  long long curve_segments = 0;     // round Hermite curve segments handed to Embree
  long long triangles = 0;          // triangles the renderer holds: leaves and trunk grids
  long long leaf_triangles = 0;
  long long points = 0;
  double height = 0.0;       // metres: highest point of any limb or leaf above the ground
  double crown_width = 0.0;  // metres: twice the largest horizontal distance from the trunk axis
  double seconds = 0.0;      // time spent growing
  bool has_geometry = false;
  GeometryStats geometry;
  double geometry_seconds = 0.0;

  long long stems() const;  // all levels, clones included
};

TreeStats compute_stats(const Skeleton& skeleton);
// Adds the counts of the renderer's geometry (curve segments, grids, triangles, bytes).
void add_geometry_stats(TreeStats& stats, const GeometryStats& geometry, double seconds);

// One JSON object with the contract's keys (and a few more), for `--stats --json`.
std::string stats_json(const TreeStats& stats, const std::string& species, unsigned long long seed,
                       long long mesh_triangles);
// Human-readable lines for `--stats`.
std::string stats_text(const TreeStats& stats);

}  // namespace arbor::generator
