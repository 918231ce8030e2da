// TreeGeometry: what the tracer renders, as plain data with no Embree dependency — limbs as exact
// round Hermite curve segments, the flared and lobed trunk as a displaced grid, leaves as cards
// (a rectangle each, the outline cut out at the hit) and free-form triangles, per-primitive
// material ids, and what is needed for bark coordinates at a hit.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "generator/geometry/leaf_bend.h"
#include "generator/geometry/leaf_margin.h"
#include "generator/skeleton.h"

namespace arbor::generator {

enum MaterialId : std::uint16_t {
  kMaterialBark = 0,
  kMaterialLeafFront = 1,
  kMaterialLeafBack = 2
};

// Metadata of one curve segment.
struct CurveSegment {
  std::int32_t limb = 0;
  float arc0 = 0.0f, arc1 = 0.0f;          // bark arc length (m) at u = 0 and u = 1
  glm::vec3 normal0{0.0f}, normal1{0.0f};  // rotation-minimising frame normal at the ends
  std::uint16_t material = kMaterialBark;
  // Level of detail at range (scene/lod.h, Weber & Penn §5): the item's level (0 trunk, 1 main
  // branches, 2 the deeper stems; kNoLod: never thinned) and its index among that level's segments
  // in the order they were made.
  std::uint8_t lod_level = 0;
  std::uint32_t lod_item = 0;
  glm::vec3 color{1.0f};  // multiplies the material's albedo (TREE-MAKER colours)
};
inline constexpr std::uint8_t kNoLod = 0xff;

// Embree's ROUND_HERMITE_CURVE layout: segment i uses points[2i], points[2i+1] (x, y, z, radius)
// and tangents[2i], tangents[2i+1] (their derivatives with respect to u in [0, 1]).
struct CurveSet {
  std::vector<glm::vec4> points;
  std::vector<glm::vec4> tangents;
  std::vector<CurveSegment> segments;

  std::size_t size() const { return segments.size(); }
  glm::vec4 position(std::size_t i, float u) const;           // (x, y, z, radius)
  glm::vec4 derivative(std::size_t i, float u) const;         // d/du of (x, y, z, radius)
  glm::vec4 second_derivative(std::size_t i, float u) const;  // d²/du² of (x, y, z, radius)
};

// One displaced surface of a trunk limb: width vertices around (the last column repeats the
// first, at azimuth 2π) by height rings along, row-major from startVertex (Embree's RTCGrid).
struct DisplacedGrid {
  std::uint32_t first_vertex = 0;
  std::uint16_t width = 0, height = 0;
  std::int32_t limb = 0;
  std::uint16_t material = kMaterialBark;
};

struct GridSet {
  std::vector<glm::vec3> vertices;
  std::vector<glm::vec3> normals;  // of the displaced surface (for shading)
  std::vector<glm::vec2> bark;     // (arc length along, radius × azimuth around)
  std::vector<DisplacedGrid> grids;
};

// Two-sided leaf triangles: the front material faces along the leaf normal (counter-clockwise
// winding), the back material the other way.
struct LeafMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;                        // three per triangle
  std::vector<std::uint16_t> front_material, back_material;  // per triangle
  std::vector<std::int32_t> leaf;                            // per triangle: Skeleton leaf index
  std::vector<glm::vec3> color;  // per triangle: multiplies R and T (1 unless the model colours)
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// A leaf of a LeafShape as one planar rectangle per flat panel (one; three when hinged), its
// outline cut out by LeafOutline::contains at the hit: 4 corners instead of the 13 to 49 vertices
// and 12 to 80 triangles of its triangulation. Card i's corners are corners[4i .. 4i+3]: leaf
// points (x0, y0), (x1, y0), (x1, y1), (x0, y1) — Embree's quad, u across, v along.
struct LeafCard {
  std::int32_t leaf = 0;                 // Skeleton leaf index
  std::uint16_t shape = 0;               // leaf_shape() index (a margin's derived shape too)
  float x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // the rectangle in leaf coordinates
  // The leaf point at quad coordinates (u, v).
  glm::vec2 leaf_point(float u, float v) const { return {x0 + u * (x1 - x0), y0 + v * (y1 - y0)}; }
  // The leaf point a card is enlarged about (level of detail, scene/lod.h): the leaf's middle
  // for a flat card or the middle panel, the hinge line for a side panel, so every panel stays in
  // its own plane and the panels still meet.
  glm::vec2 centre() const { return {std::clamp(0.0f, x0, x1), 0.5f * (y0 + y1)}; }
};

struct LeafCards {
  std::vector<glm::vec3> corners;  // four per card
  // Shaped leaves (leaf_bend.h) only: the bent surface's unit normal at each corner, on the front
  // side, for smooth shading across the panels (bilinear over the card's u, v); empty otherwise
  // (a flat card shades with its face's normal).
  std::vector<glm::vec3> normals;
  std::vector<LeafCard> cards;
  std::size_t size() const { return cards.size(); }
};

// Bloomenthal §6's ramiform: the surface at a fork of the trunk or a main branch, joining the
// parent limb's surface to the child's without the crease of two overlapping tubes (docs/
// geometry.md, "Ramiform"). Each fork is a collar of kRamiformSides × kRamiformRows quads, row 0
// on the parent's surface around where the child leaves it, the last row the child's "disk",
// as two triangles per quad; vertices carry the surfaces' own normals and bark coordinates at
// both edges, blended between.
inline constexpr std::uint32_t kRamiformSides = 32, kRamiformRows = 8;
struct RamiformFork {
  std::int32_t parent_limb = 0, child_limb = 0;
  std::uint32_t first_vertex = 0;  // (kRamiformRows + 1) rows of (kRamiformSides + 1) vertices
  std::uint8_t lod_level = 0;      // the child's first segment's (CurveSegment::lod_level)
  std::uint32_t lod_item = 0;
};
struct RamiformSet {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec3> tangents;     // along the bark (the limbs' axes, blended)
  std::vector<glm::vec3> bark;         // (along, azimuth, radius), as BarkCoordinates
  std::vector<std::uint32_t> indices;  // three per triangle; fork k's are 2·sides·rows·k onwards
  std::vector<RamiformFork> forks;
  static constexpr std::uint32_t kTrianglesPerFork = 2 * kRamiformSides * kRamiformRows;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

struct GeometryStats {
  std::size_t limbs = 0;
  std::size_t curve_segments = 0;
  std::size_t tension_raised_limbs = 0;  // start tension raised to keep radius < curvature radius
  std::size_t radius_adjusted_segments = 0;  // where radius ≥ radius of curvature was reduced
  std::size_t grids = 0, grid_vertices = 0, grid_triangles = 0;
  std::size_t leaf_triangles = 0;  // free-form (TREE-MAKER) leaf triangles
  std::size_t leaf_cards = 0;
  std::size_t leaf_outline_triangles = 0;  // the cards' leaves' outlines (leaf_cards.h)
  // Forks large enough for a collar (docs/geometry.md, "Ramiform"), of them collared, skipped
  std::size_t ramiform_forks = 0, ramiforms = 0, ramiform_triangles = 0;
  std::size_t ramiforms_skipped = 0;  // forks where no collar fits (docs/geometry.md)
  std::size_t ramiform_trunk_forks = 0, ramiform_trunk_collars = 0;  // of them, the trunk's
  std::size_t bytes = 0;                                             // of all the arrays above
  bool built = true;  // false: counted by count_tree_geometry (bytes and adjustments unknown)
};

struct TreeGeometry {
  CurveSet curves;
  GridSet grids;
  LeafMesh leaves;        // free-form leaf triangles (TREE-MAKER's tri=)
  LeafCards cards;        // every leaf of a LeafShape
  RamiformSet ramiforms;  // GeometryOptions::ramiform
  GeometryStats stats;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};
  // Items of each level of detail (scene/lod.h): curve segments of levels 0, 1 and 2+, and the
  // shaped leaves (a card's `leaf` is its item; free-form leaf triangles are never thinned).
  std::array<std::uint32_t, 4> lod_items{};
};

enum class LeafStyle { Flat, Hinged, Shaped };

struct GeometryOptions {
  bool displace_trunk = true;  // trunks with Flare or Lobes become displaced grids
  double grid_step = 0.25;     // axial step of the trunk grid, × the local radius
  int grid_sides = 0;          // around the trunk; 0: max(64, 16 × Lobes)
  LeafStyle leaf_style = LeafStyle::Flat;
  double hinge_angle = 20.0;          // degrees each side panel folds up (Bloomenthal §10)
  double hinge_position = 1.0 / 6.0;  // hinges at x = ±this, across a leaf of unit width
  LeafBend leaf_bend;                 // LeafStyle::Shaped: fold, cup, curl and twist
  // The leaf's stalk (leaf_cards.h): its length × the blade's length (0: none) and its width ×
  // the blade's width.
  double petiole_length = 0.0, petiole_width = 0.03;
  LeafMarginSpec leaf_margin;  // the leaves' margin (leaf_margin.h); entire: the outline as is
  int buttresses = 0;          // root buttresses at the trunk's base (RootLook)
  double buttress_height = 3.0, buttress_spread = 2.0;  // × the trunk's base radius
  bool ramiform = false;  // Bloomenthal §6 surfaces at the trunk's and main branches' forks
  // Degrees: the trunk continued straight down below its base, far enough that on a slope this
  // steep its downhill side still reaches the ground (tan(slope) × the base's reach, + 1 cm);
  // 0: not (a tree on the flat plane). trunk_sink.cpp.
  double sink_slope = 0.0;
};

// Continues the trunk below the tree's base by GeometryOptions::sink_slope (its first ring of a
// displaced trunk, or its first curve segment, repeated straight down).
void sink_trunk(const Skeleton& skeleton, double slope_degrees, TreeGeometry& g);

TreeGeometry build_tree_geometry(const Skeleton& skeleton, const GeometryOptions& options = {});

// Every leaf as triangles (the cards' outlines triangulated as LeafShape gives them, hinged
// leaves sharing their hinge vertices; then the free-form triangles): for meshes and exports.
LeafMesh leaf_triangles(const TreeGeometry& geometry);

// Geometry options a species asks for (its leaf hinge, its root buttresses), defaults otherwise.
struct Species;
GeometryOptions geometry_options_for(const Species& species);

// Bloomenthal §8 bark coordinates: arc length along the limb and circumferential distance
// (radius × azimuth from the frame normal), continuous along a limb.
struct BarkCoordinates {
  float along = 0.0f;
  float around = 0.0f;
  float azimuth = 0.0f;  // radians in [0, 2π)
  float radius = 0.0f;   // of the limb there (without displacement)
};
BarkCoordinates curve_bark(const CurveSet& curves, std::size_t segment, float u,
                           const glm::vec3& point);
BarkCoordinates grid_bark(const GridSet& grids, std::size_t grid, float u, float v);
glm::vec3 grid_normal(const GridSet& grids, std::size_t grid, float u, float v);

}  // namespace arbor::generator
