// Leaf outlines built from radial functions about a centre, so each part is star-shaped and a
// triangle fan from its centre triangulates it exactly.
#include "generator/geometry/leaf_shapes.h"

#include <cmath>
#include <functional>
#include "common/math.h"

namespace arbor::gen {

namespace {


// Adds one star-shaped part: `radius(theta)` (theta from the +y axis, counter-clockwise) about
// `centre`, scaled by `sx, sy` and rotated by `tilt` (radians).
void add_part(LeafShape& shape, glm::dvec2 centre, double sx, double sy, double tilt, int samples,
              const std::function<double(double)>& radius) {
  const auto first = static_cast<std::uint32_t>(shape.vertices.size());
  shape.vertices.emplace_back(centre);
  const double c = std::cos(tilt), s = std::sin(tilt);
  for (int k = 0; k < samples; ++k) {
    const double theta = 2.0 * kPi * k / samples;
    const double r = radius(theta);
    const double px = -std::sin(theta) * r * sx;  // theta = 0 points at the tip (+y)
    const double py = std::cos(theta) * r * sy;
    shape.vertices.emplace_back(centre.x + c * px - s * py, centre.y + s * px + c * py);
  }
  for (int k = 0; k < samples; ++k) {
    const auto a = first + 1 + static_cast<std::uint32_t>(k);
    const auto b = first + 1 + static_cast<std::uint32_t>((k + 1) % samples);
    shape.triangles.push_back({first, a, b});
  }
}

LeafShape make_oval() {
  LeafShape s{"oval", {}, {}};
  add_part(s, {0.0, 0.5}, 1.0, 1.0, 0.0, 12, [](double) { return 0.5; });
  return s;
}

LeafShape make_triangle() {
  // A broad-based triangle: base corners at the attachment, tip at y = 1.
  LeafShape s{"triangle", {{-0.5f, 0.0f}, {0.5f, 0.0f}, {0.0f, 1.0f}}, {{0, 1, 2}}};
  return s;
}

// Lobed outline with `lobes` rounded (power 2) or pointed (higher power) peaks, one at the tip
// and a notch at the base.
LeafShape make_lobed(std::string_view name, int lobes, double floor, double power) {
  LeafShape s{name, {}, {}};
  add_part(s, {0.0, 0.5}, 1.0, 1.0, 0.0, 16 * lobes, [=](double theta) {
    const double peak = std::pow(std::fabs(std::cos(0.5 * lobes * theta)), power);
    return 0.5 * (floor + (1.0 - floor) * peak);
  });
  return s;
}

LeafShape make_leaflets() {
  LeafShape s{"3 leaflets", {}, {}};
  auto oval = [](double) { return 0.5; };
  add_part(s, {0.0, 0.68}, 0.34, 0.62, 0.0, 10, oval);            // terminal leaflet
  add_part(s, {-0.24, 0.34}, 0.26, 0.5, 0.9, 10, oval);           // left leaflet
  add_part(s, {0.24, 0.34}, 0.26, 0.5, -0.9, 10, oval);           // right leaflet
  return s;
}

}  // namespace

const std::vector<LeafShape>& leaf_shapes() {
  static const std::vector<LeafShape> shapes = {
      make_oval(),
      make_triangle(),
      make_lobed("3-lobe oak", 3, 0.55, 2.0),
      make_lobed("3-lobe maple", 3, 0.35, 6.0),
      make_lobed("5-lobe maple", 5, 0.4, 6.0),
      make_leaflets(),
  };
  return shapes;
}

std::size_t leaf_shape_count() { return leaf_shapes().size(); }

}  // namespace arbor::gen
