// Leaves of a LeafShape as cards (LeafCards): one flat card, Bloomenthal's three hinged panels
// (§10), or a shaped leaf's grid of panels on its bent surface (leaf_bend.h), each leaf's cards
// consecutive; and the stalk (petiole) each leaf hangs on, as a thin round curve.
#pragma once

#include <vector>

#include "generator/geometry/leaf_shapes.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::generator {

// Where a leaf's panels are cut, in leaf coordinates: across at xs (from the outline's lo.x to
// hi.x), along at ys (lo.y to hi.y). A leaf has (xs.size() − 1) × (ys.size() − 1) cards, row by
// row from the base.
struct LeafPanels {
  std::vector<float> xs, ys;
  std::size_t cards() const { return (xs.size() - 1) * (ys.size() - 1); }
};
LeafPanels leaf_panels(const LeafOutline& outline, const GeometryOptions& options);

// Every leaf of the skeleton as its cards (with their corners' shading normals when shaped) and,
// with options.petiole_length > 0, its petiole: the blade moved out along the leaf's axis by the
// petiole's length and a curve from the leaf's point on its stem to the blade's base.
void add_leaf_cards(const Skeleton& skeleton, const GeometryOptions& options, TreeGeometry& g);

// The petiole's curve segments add_leaf_cards makes for the skeleton (for the counts).
std::size_t petiole_segments(const Skeleton& skeleton, const GeometryOptions& options);

// The outline each LeafShape's leaves are drawn with (by LeafShape index): the shape with the
// options' margin, for the proportions of the skeleton's leaves of that shape (their mean width
// over length); the shape itself without a margin.
std::vector<std::size_t> drawn_leaf_shapes(const Skeleton& skeleton,
                                           const GeometryOptions& options);

// The triangles of every leaf's drawn outline, as leaf_triangles would make them before its
// panels' cuts (the statistics' leaf triangles).
std::size_t leaf_outline_triangles(const Skeleton& skeleton, const GeometryOptions& options);

}  // namespace arbor::generator
