// Bloomenthal §6, the ramiform (docs/geometry.md, "Ramiform"): at each fork of the trunk and of
// the main branches, a collar joining the parent limb's rendered surface (its round curve, or
// the displaced grid of a flared and lobed trunk) to the child's round curve. The paper's disks
// "far enough along the outgoing limbs so as not to interpenetrate" become the collar's last
// row, a ring on the child just beyond where its tube leaves the parent's; the collar's first
// row is a ring on the parent's surface around that footprint; between them each column is a
// cubic Hermite spline leaving the parent tangent to its surface and reaching the child tangent
// to its surface (the paper's two-segment splines and saddle, for a fork whose parent goes on).
#pragma once

#include <vector>

#include "generator/geometry/limbs.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::generator {

// Adds a collar to g.ramiforms for every fork of a limb of level 0 or 1 whose child is a round
// curve, after the limbs' curves and grids are built. A fork where the child never leaves the
// parent's surface, leaves it at once, or is too short for its disk is counted in
// g.stats.ramiforms_skipped and keeps its crease.
void add_ramiforms(const std::vector<Limb>& limbs, TreeGeometry& g);

// The ramiform's counts in `s` (ramiform_forks, ramiforms, ramiform_triangles, the skipped and
// the trunk's), exactly as a build finds them: the limbs and their collars are built (the leaves
// are not) and thrown away. For `grow --stats`, which otherwise counts without building
// (count_tree_geometry). Defined in tree_geometry.cpp, beside the limbs' construction.
void count_ramiforms(const Skeleton& skeleton, const std::vector<Limb>& limbs,
                     const GeometryOptions& options, GeometryStats& s);

}  // namespace arbor::generator
