// The LeafShape outlines of Weber & Penn §4.5, triangulated, in unit leaf coordinates.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

namespace arbor::gen {

// A leaf outline: x across the blade in [-0.5, 0.5], y along it in [0, 1] from the base (where
// the leaf attaches) to the tip. uv = (x + 0.5, y).
struct LeafShape {
  std::string_view name;
  std::vector<glm::vec2> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from the front
};

// Shapes by LeafShape index: 0 oval, 1 triangle, 2 3-lobe oak, 3 3-lobe maple, 4 5-lobe maple,
// 5 3 leaflets.
const std::vector<LeafShape>& leaf_shapes();
std::size_t leaf_shape_count();

}  // namespace arbor::gen
