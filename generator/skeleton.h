// The Skeleton: Bloomenthal's "points and connections", the one interchange every tree model emits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace arbor::generator {

// A point on a limb's axis with the limb's radius there (metres).
struct SkeletonPoint {
  glm::vec3 position{0.0f};
  float radius = 0.0f;
};

// A limb: a chain of points from its base to its tip. Connections are parent links: a stem grows
// from one point of its parent's axis (at parent_offset metres from the parent's base), so every
// point has at most one incoming limb and the stems form a tree with one root.
struct Stem {
  std::int32_t level = 0;          // 0 trunk, 1 branches, 2 sub-branches, …
  std::int32_t parent = -1;        // index of the stem it grows from; -1 only for the root
  bool is_clone = false;           // split off its parent at the same level (Weber & Penn §4.2)
  float parent_offset = 0.0f;      // metres along the parent's axis where this stem starts
  std::int32_t parent_point = -1;  // the parent's point it starts at (a branch point), or -1 when
                                   // it starts between two of the parent's points
  std::uint32_t first_point = 0;   // range in Skeleton::points; the first point is the base
  std::uint32_t point_count = 0;
  float length = 0.0f;       // metres of the whole stem (a clone shares its twin's length)
  float base_radius = 0.0f;  // radius at Z = 0 of the (unsplit) stem
  float z_start = 0.0f;      // normalised position Z of the first point (> 0 for clones)
  float taper = -1.0f;       // Weber & Penn nTaper (0–3); < 0: interpolate point radii
  glm::vec3 color{1.0f};     // multiplies the bark albedo (TREE-MAKER limb colours)
};

// A leaf blade placed on a stem. The blade spans `length` along `axis` from `position`, and
// `width` across it (along cross(normal, axis)); `normal` is the front (upper) side.
struct Leaf {
  glm::vec3 position{0.0f};
  glm::vec3 axis{0.0f, 0.0f, 1.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float length = 0.0f;
  float width = 0.0f;
  std::int32_t stem = -1;
  std::int32_t shape = 0;  // index into leaf_shapes()
};

// A free-form leaf element already placed in the tree (TREE-MAKER's tri= and ln=): a triangle
// (counter-clockwise = front) or a line drawn as a thin limb, with the albedo it multiplies.
struct LeafTriangle {
  glm::vec3 v[3]{};
  glm::vec3 color{1.0f};
  std::int32_t stem = -1;
  std::int32_t leaf = 0;  // which placed leaf it belongs to (elements of one leaf share it)
};
struct LeafLine {
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.001f;
  glm::vec3 color{1.0f};
  std::int32_t stem = -1;
  std::int32_t leaf = 0;
};

// Radial displacement of level-0 stems (Weber & Penn §4.4): flare near the base, lobed section.
struct TrunkDisplacement {
  float flare = 0.0f;
  std::int32_t lobes = 0;
  float lobe_depth = 0.0f;
};

struct Skeleton {
  std::vector<SkeletonPoint> points;
  std::vector<Stem> stems;
  std::vector<Leaf> leaves;
  std::vector<LeafTriangle> leaf_triangles;
  std::vector<LeafLine> leaf_lines;
  TrunkDisplacement trunk;
  std::int32_t levels = 1;  // number of stem levels present (max level + 1)

  // Radius of stem s at normalised position z (0 base, 1 tip), from its taper when it has one.
  float radius_at(const Stem& s, double z) const;
  // Leaves of every kind: shaped leaves plus leaves made of free-form elements.
  std::size_t leaf_count() const;
  // Position on stem s's axis at `offset` metres from the base of the whole stem.
  glm::vec3 position_at_offset(const Stem& s, double offset) const;
};

// Checks the invariants: exactly one root, parents before children (so no cycles), every stem has
// at least two points, finite values, non-negative radii, child base radius ≤ parent radius at
// the branch point. Returns "" when valid, else the first violation in words.
// Why a grown tree is out of scale: a point, leaf or leaf element that is not finite or lies more
// than 1000 km from the origin, or a limb segment shorter than 1 micrometre (numbers that
// compound, such as growth over many iterations or size ratios over many levels, can take a
// tree past what float geometry holds); "" when it is within.
std::string scale_problem(const Skeleton& skeleton);

std::string validate(const Skeleton& skeleton);

}  // namespace arbor::generator
