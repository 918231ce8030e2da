// How TreeGeometry divides a tree, shared by building it (tree_geometry.cpp) and by counting it
// without building it (`arbor grow --stats`): where a limb's curves are cut into pieces, the rings
// and sides of a displaced trunk grid, the panels of a leaf card, which leaf lines are kept.
#pragma once

#include <cstddef>
#include <vector>

#include "generator/geometry/leaf_shapes.h"
#include "generator/geometry/limbs.h"
#include "generator/geometry/tree_geometry.h"
#include "generator/skeleton.h"

namespace arbor::generator {

// A limb that becomes a displaced grid (Weber & Penn §4.4 flare and lobes, root buttresses)
// rather than curves.
bool displaced(const Skeleton& sk, const Limb& limb, const GeometryOptions& o);

// Piece boundaries (spline parameters) of a limb's curves: per spline segment 1 piece, 8 where
// the taper law is not linear in z, 32 for periodic taper, and 8 more inside any piece where the
// radius of curvature limits the radius (so the cubic radius follows the limit closely). Pieces
// are exact sub-segments of the spline; `limited` says which ones the curvature limits.
void limb_pieces(const Skeleton& sk, const Limb& limb, std::vector<double>& ts,
                 std::vector<bool>& limited);

// The rings of a displaced trunk grid: spline parameters, a step of grid_step × the flared radius
// (half that in the lowest eighth, where the flare changes fastest).
std::vector<double> grid_rings(const Skeleton& sk, const Limb& limb, const GeometryOptions& o);
// Vertices around a displaced trunk grid (its columns less the closing one).
int grid_sides(const Skeleton& sk, const GeometryOptions& o);

// A TREE-MAKER leaf line long enough to be drawn as a thin limb.
bool kept_as_line(const LeafLine& line);

// The counts of build_tree_geometry's statistics without building it: limbs, curve segments,
// grids and their vertices and triangles, leaf cards and free-form triangles. `built` is false;
// the sizes only a build knows (bytes, radius-adjusted segments) are 0. With o.ramiform the
// collars cannot be counted without trying them: the limbs and collars are built (not the
// leaves) and their counts are a build's (count_ramiforms).
GeometryStats count_tree_geometry(const Skeleton& sk, const GeometryOptions& o);

}  // namespace arbor::generator
