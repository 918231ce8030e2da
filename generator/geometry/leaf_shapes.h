// The LeafShape outlines of Weber & Penn §4.5, triangulated, in unit leaf coordinates.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

namespace arbor::generator {

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

// Shapes made from those while the program runs (a margin's teeth, leaf_margin.h), numbered on
// from leaf_shape_count(): the index of the shape `make` builds, built once for each `key` and
// kept (at most 4096 of them). Safe to call from several threads; which index a key gets may
// depend on the threads' order, so an index is never written out, only used to find the shape.
std::size_t derived_leaf_shape(const std::string& key, const std::function<LeafShape()>& make);

// A shape by index, LeafShape's or derived.
const LeafShape& leaf_shape(std::size_t index);

// The outline as a point test, for leaves rendered as one rectangle each (a card) with the shape
// cut out at the hit: the union of star-shaped parts, each a polygon whose fan from its centre is
// exactly the shape's triangulation above.
struct LeafOutline {
  struct Part {
    glm::vec2 centre{0.0f};
    std::vector<glm::vec2> vertices;  // counter-clockwise about the centre
    std::vector<float> turn;  // each vertex's angle about the centre from the first's, [0, 2π)
    float inner = 0.0f, outer = 0.0f;  // every point nearer the centre is inside; farther, outside
    bool contains(glm::vec2 p) const;  // in one of the part's fan triangles, edges included
  };
  std::vector<Part> parts;
  glm::vec2 lo{0.0f}, hi{0.0f};  // bounding box in leaf coordinates
  // Whether leaf point (x across in [-0.5, 0.5], y along in [0, 1]) lies in the leaf: in one of
  // the fan's triangles, edges included.
  bool contains(glm::vec2 p) const;
};

// The outline of a shape by index, LeafShape's or derived.
const LeafOutline& leaf_outline(std::size_t shape);

}  // namespace arbor::generator
