// A leaf's margin (leaf_margin.h): the outline's parts resampled along their edges and each point
// moved towards its part's centre by the tooth's profile.
#include "generator/geometry/leaf_margin.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "common/math.h"
#include "generator/geometry/leaf_shapes.h"

namespace arbor::generator {

namespace {

constexpr int kSamplesPerTooth = 12;  // a serrate tooth's point falls on a sample (9 of 12)
constexpr double kSerrateTip = 0.75;  // the phase of a serrate tooth's point

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// A part's ring as closed polyline in the leaf's proportions (x × aspect, y), its length.
double ring_length(const LeafOutline::Part& part, double aspect) {
  double length = 0.0;
  for (std::size_t k = 0; k < part.vertices.size(); ++k) {
    const glm::dvec2 a = part.vertices[k], b = part.vertices[(k + 1) % part.vertices.size()];
    length += std::hypot((b.x - a.x) * aspect, b.y - a.y);
  }
  return length;
}

// Whether the point lies inside another part of the outline (an edge there is no margin).
bool covered(const LeafOutline& o, std::size_t own, glm::vec2 p) {
  for (std::size_t i = 0; i < o.parts.size(); ++i) {
    if (i != own && o.parts[i].contains(p)) return true;
  }
  return false;
}

}  // namespace

double margin_profile(LeafMargin kind, double phase) {
  switch (kind) {
    case LeafMargin::Serrate:  // a long back rising to the point, a steep front into the notch
      return phase < kSerrateTip ? 1.0 - phase / kSerrateTip
                                 : (phase - kSerrateTip) / (1.0 - kSerrateTip);
    case LeafMargin::Crenate: {  // half-disc teeth meeting in sharp notches
      const double x = 2.0 * phase - 1.0;
      return 1.0 - std::sqrt(std::max(0.0, 1.0 - x * x));
    }
    case LeafMargin::Lobed: return 0.5 * (1.0 - std::cos(2.0 * kPi * phase));
    case LeafMargin::Entire:
    default: return 0.0;
  }
}

LeafShape margined_shape(const LeafOutline& base, const LeafMarginSpec& margin, double aspect) {
  LeafShape shape{"margined", {}, {}};
  // The teeth's spacing: the outline's edge, half of it a side, over the teeth of a side; each
  // part then takes a whole number of teeth so its ring closes on a whole tooth.
  double perimeter = 0.0;
  for (const LeafOutline::Part& part : base.parts) perimeter += ring_length(part, aspect);
  const double spacing = 0.5 * perimeter / margin.teeth;
  const double lo = base.lo.y, height = base.hi.y - base.lo.y;
  for (std::size_t pi = 0; pi < base.parts.size(); ++pi) {
    const LeafOutline::Part& part = base.parts[pi];
    const double length = ring_length(part, aspect);
    const double teeth = std::max(1.0, std::round(length / spacing));
    const double tooth = length / teeth, step = tooth / kSamplesPerTooth;
    const glm::dvec2 c = part.centre;
    const auto centre = static_cast<std::uint32_t>(shape.vertices.size());
    shape.vertices.push_back(part.centre);
    double along = 0.0;  // arc length from the ring's first vertex
    for (std::size_t k = 0; k < part.vertices.size(); ++k) {
      const glm::dvec2 a = part.vertices[k], b = part.vertices[(k + 1) % part.vertices.size()];
      const double edge = std::hypot((b.x - a.x) * aspect, b.y - a.y);
      // The edge's first vertex, then a point at every step of the ring's arc length (so that
      // every tooth's point and notch is a vertex).
      const double first_step = std::floor(along / step) + 1.0;
      for (double m = first_step - 1.0; m < first_step || m * step < along + edge - 1e-9 * step;
           m += 1.0) {
        const double t = m < first_step ? 0.0 : (m * step - along) / edge;
        const glm::dvec2 p = a + (b - a) * t;
        double phase = std::fmod((along + t * edge) / tooth, 1.0);
        if (b.y < a.y) phase = 1.0 - phase;  // teeth point towards the tip on either side
        // Fading in above the base (the petiole's end) and out at the tip.
        double weight = smoothstep(lo + 0.03 * height, lo + 0.18 * height, p.y) *
                        (1.0 - smoothstep(lo + 0.95 * height, lo + height, p.y));
        if (weight > 0.0 && covered(base, pi, glm::vec2(p))) weight = 0.0;
        const glm::dvec2 r = p - c;
        const double reach = std::hypot(r.x * aspect, r.y);  // in the leaf's proportions
        // The cut, × the blade's width (aspect × its length), at most 80 % of the way in.
        const double cut = std::min(
            margin.depth * aspect * weight * margin_profile(margin.kind, phase), 0.8 * reach);
        shape.vertices.emplace_back(reach > 0.0 ? c + r * (1.0 - cut / reach) : p);
      }
      along += edge;
    }
    const auto ring = static_cast<std::uint32_t>(shape.vertices.size()) - centre - 1;
    for (std::uint32_t k = 0; k < ring; ++k)
      shape.triangles.push_back({centre, centre + 1 + k, centre + 1 + (k + 1) % ring});
  }
  return shape;
}

std::size_t margined_shape_index(std::size_t base, const LeafMarginSpec& margin, double aspect) {
  if (margin.entire() || !(aspect > 0.0)) return base;
  const double octaves = std::round(std::log2(aspect) * 32.0);
  const double rounded = std::exp2(octaves / 32.0);
  char key[160];
  std::snprintf(key, sizeof key, "margin %zu %d %d %.17g %.0f", base, static_cast<int>(margin.kind),
                margin.teeth, margin.depth, octaves);
  return derived_leaf_shape(key,
                            [&] { return margined_shape(leaf_outline(base), margin, rounded); });
}

}  // namespace arbor::generator
