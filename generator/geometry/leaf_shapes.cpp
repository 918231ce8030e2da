// Leaf outlines built from radial functions about a centre, so each part is star-shaped and a
// triangle fan from its centre triangulates it exactly.
#include "generator/geometry/leaf_shapes.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <cmath>
#include <functional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include "common/error.h"
#include "common/math.h"

namespace arbor::generator {

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
  add_part(s, {0.0, 0.68}, 0.34, 0.62, 0.0, 10, oval);   // terminal leaflet
  add_part(s, {-0.24, 0.34}, 0.26, 0.5, 0.9, 10, oval);  // left leaflet
  add_part(s, {0.24, 0.34}, 0.26, 0.5, -0.9, 10, oval);  // right leaflet
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

namespace {

float cross2(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

// The fan's parts: a fan triangle is (centre, a, b) with the centre shared by the part's
// triangles; the single triangle shape is the fan of its centroid.
LeafOutline outline_of(const LeafShape& shape) {
  LeafOutline o;
  std::vector<std::array<std::uint32_t, 3>> tris = shape.triangles;
  if (tris.size() == 1) {  // one triangle: its centroid's fan of three
    const auto& t = tris[0];
    LeafOutline::Part part;
    part.centre = (shape.vertices[t[0]] + shape.vertices[t[1]] + shape.vertices[t[2]]) / 3.0f;
    for (std::uint32_t i : t) part.vertices.push_back(shape.vertices[i]);
    o.parts.push_back(part);
  } else {
    for (std::size_t k = 0; k < tris.size();) {  // consecutive triangles sharing a centre
      LeafOutline::Part part;
      const std::uint32_t centre = tris[k][0];
      part.centre = shape.vertices[centre];
      for (; k < tris.size() && tris[k][0] == centre; ++k)
        part.vertices.push_back(shape.vertices[tris[k][1]]);
      o.parts.push_back(part);
    }
  }
  o.lo = o.hi = o.parts[0].vertices[0];
  for (LeafOutline::Part& part : o.parts) {
    const glm::vec2 c = part.centre;
    const float first = std::atan2(part.vertices[0].y - c.y, part.vertices[0].x - c.x);
    part.inner = 1e30f;
    for (std::size_t k = 0; k < part.vertices.size(); ++k) {
      const glm::vec2 a = part.vertices[k], b = part.vertices[(k + 1) % part.vertices.size()];
      float turn = std::atan2(a.y - c.y, a.x - c.x) - first;
      if (turn < 0.0f) turn += 6.2831853f;
      part.turn.push_back(k == 0 ? 0.0f : turn);
      part.outer = std::max(part.outer, glm::length(a - c));
      // Distance from the centre to the edge's line (the centre lies inside every fan triangle).
      part.inner = std::min(part.inner, cross2(b - a, c - a) / glm::length(b - a));
      o.lo = glm::min(o.lo, a);
      o.hi = glm::max(o.hi, a);
    }
    part.inner *= 0.999f;  // float rounding: a point this near the centre is surely inside
    part.outer *= 1.001f;
  }
  return o;
}

}  // namespace

bool LeafOutline::Part::contains(glm::vec2 p) const {
  const glm::vec2 d = p - centre;
  const float r2 = glm::dot(d, d);
  if (r2 <= inner * inner) return true;
  if (r2 > outer * outer) return false;
  // The fan triangle whose angular sector holds p, then the side of its outer edge.
  const glm::vec2 v0 = vertices[0] - centre;
  float angle = std::atan2(cross2(v0, d), glm::dot(v0, d));
  if (angle < 0.0f) angle += 6.2831853f;
  const auto it = std::upper_bound(turn.begin(), turn.end(), angle);
  const std::size_t k = static_cast<std::size_t>(it - turn.begin()) - 1;
  const glm::vec2 a = vertices[k], b = vertices[(k + 1) % vertices.size()];
  return cross2(b - a, p - a) >= 0.0f;
}

bool LeafOutline::contains(glm::vec2 p) const {
  for (const Part& part : parts) {
    if (part.contains(p)) return true;
  }
  return false;
}

namespace {

// The derived shapes: each made once under the lock and published into its slot, so readers
// (the renderer's leaf filter, on every card hit) take no lock.
struct Derived {
  LeafShape shape;
  LeafOutline outline;
};
constexpr std::size_t kMaxDerived = 4096;
std::array<std::atomic<const Derived*>, kMaxDerived> derived_slots{};

const Derived& derived(std::size_t index) {
  const std::size_t k = index - leaf_shape_count();
  const Derived* d = k < kMaxDerived ? derived_slots[k].load(std::memory_order_acquire) : nullptr;
  if (d == nullptr) check_failed("the derived leaf shape exists", __FILE__, __LINE__);
  return *d;
}

}  // namespace

std::size_t derived_leaf_shape(const std::string& key, const std::function<LeafShape()>& make) {
  static std::mutex lock;
  static std::map<std::string, std::size_t> index_of;
  const std::lock_guard<std::mutex> hold(lock);
  const auto found = index_of.find(key);
  if (found != index_of.end()) return found->second;
  const std::size_t k = index_of.size();
  if (k >= kMaxDerived) {
    throw RuntimeFailure("more than " + std::to_string(kMaxDerived) +
                         " distinct leaf margins in one run");
  }
  auto* d = new Derived{make(), {}};  // kept for the program's life, as the base shapes are
  d->outline = outline_of(d->shape);
  derived_slots[k].store(d, std::memory_order_release);
  const std::size_t index = leaf_shape_count() + k;
  index_of.emplace(key, index);
  return index;
}

const LeafShape& leaf_shape(std::size_t index) {
  return index < leaf_shape_count() ? leaf_shapes()[index] : derived(index).shape;
}

const LeafOutline& leaf_outline(std::size_t shape) {
  static const std::vector<LeafOutline> outlines = [] {
    std::vector<LeafOutline> v;
    for (const LeafShape& s : leaf_shapes()) v.push_back(outline_of(s));
    return v;
  }();
  return shape < outlines.size() ? outlines[shape] : derived(shape).outline;
}

}  // namespace arbor::generator
