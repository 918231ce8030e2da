#include "generator/geometry/geometry_plan.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "generator/geometry/leaf_cards.h"
#include "generator/geometry/ramiform.h"
#include "generator/models/weber_penn/weber_penn_formulas.h"

namespace arbor::generator {

namespace {

// Sub-pieces per spline segment: radius laws that are not linear in z need more.
int pieces_for(const Skeleton& sk, const Limb& limb, std::size_t segment) {
  const Stem& s = sk.stems[static_cast<size_t>(limb.segment_stem(segment))];
  // Periodic taper (Weber & Penn §4.3, nTaper in (2, 3]) swells the limb between joins where the
  // radius has unbounded slope: enough pieces to follow each swelling.
  if (s.taper > 2.0f) return 32;
  return s.taper > 1.0f ? 8 : 1;
}

// Whether radius × curvature reaches 0.9 on the piece [a, b] of spline segment `segment`, at 33
// cosine-spaced points (dense near the ends, where a short clamped tangent makes the curvature
// peak). The spacing is tabulated once and the samples located from their segment (perf:
// CubicSpline::curvature and locate were 20–28 % of `grow --stats` for the willow, issue 31);
// the values are the same bits.
bool curvature_limits(const Skeleton& sk, const Limb& limb, std::size_t segment, double a,
                      double b) {
  static const std::array<double, 33> spacing = [] {
    std::array<double, 33> f{};
    for (int k = 0; k <= 32; ++k) f[static_cast<size_t>(k)] = 1.0 - std::cos(kPi * k / 32.0);
    return f;
  }();
  for (const double f : spacing) {
    const double t = a + (b - a) * 0.5 * f;
    double u = 0.0;
    const std::size_t i = limb.spline.locate_from(segment, t, u);
    if (limb.radius_in(sk, i, u) * limb.spline.curvature_in(i, u) >= 0.9) return true;
  }
  return false;
}

}  // namespace

bool displaced(const Skeleton& sk, const Limb& limb, const GeometryOptions& o) {
  return o.displace_trunk && limb.level == 0 &&
         (sk.trunk.flare > 0.0f || (sk.trunk.lobes > 0 && sk.trunk.lobe_depth > 0.0f) ||
          o.buttresses > 0);
}

void limb_pieces(const Skeleton& sk, const Limb& limb, std::vector<double>& ts,
                 std::vector<bool>& limited) {
  const CubicSpline& spline = limb.spline;
  for (std::size_t k = 0; k < spline.segment_count(); ++k) {
    const int m = pieces_for(sk, limb, k);
    for (int j = 0; j < m; ++j) {
      const double a = spline.params[k] + (spline.params[k + 1] - spline.params[k]) * j / m;
      const double b = spline.params[k] + (spline.params[k + 1] - spline.params[k]) * (j + 1) / m;
      const bool limit = curvature_limits(sk, limb, k, a, b);
      const int sub = limit ? 8 : 1;
      for (int q = 0; q < sub; ++q) {
        ts.push_back(a + (b - a) * q / sub);
        limited.push_back(limit);
      }
    }
  }
  ts.push_back(spline.params.back());
}

std::vector<double> grid_rings(const Skeleton& sk, const Limb& limb, const GeometryOptions& o) {
  const double total = limb.spline.params.back();
  const double base_radius = limb.radius_at(sk, 0.0);
  std::vector<double> ts{0.0};
  while (ts.back() < total && ts.size() < 32000) {
    const double t = ts.back();
    const double z = limb.z_at(sk, t);
    const double r =
        std::max(limb.radius_at(sk, t), 0.25 * base_radius) * wp::flare_scale(sk.trunk.flare, z);
    const double step = o.grid_step * r * (z < 0.125 ? 0.5 : 1.0);
    ts.push_back(std::min(total, t + std::max(step, total * 1e-4)));
  }
  return ts;
}

int grid_sides(const Skeleton& sk, const GeometryOptions& o) {
  return std::clamp(
      o.grid_sides > 0 ? o.grid_sides : std::max({64, 16 * sk.trunk.lobes, 32 * o.buttresses}), 8,
      4096);
}

bool kept_as_line(const LeafLine& line) {
  return glm::length(line.b - line.a) > 2.0f * line.radius;
}

GeometryStats count_tree_geometry(const Skeleton& sk, const GeometryOptions& o) {
  GeometryStats s;
  s.built = false;
  const std::vector<Limb> limbs = fit_limbs(sk);
  s.limbs = limbs.size();
  std::vector<double> ts;
  std::vector<bool> limited;
  for (const Limb& limb : limbs) {
    s.tension_raised_limbs += limb.tension_raised ? 1u : 0u;
    if (displaced(sk, limb, o)) {
      const std::size_t rings = grid_rings(sk, limb, o).size();
      const auto sides = static_cast<std::size_t>(grid_sides(sk, o));
      ++s.grids;
      s.grid_vertices += rings * (sides + 1);
      s.grid_triangles += 2 * sides * (rings - 1);
    } else {
      ts.clear();
      limited.clear();
      limb_pieces(sk, limb, ts, limited);
      s.curve_segments += ts.size() - 1;
    }
  }
  std::vector<std::size_t> cards_of(leaf_shape_count(), 0);  // per shape, found once
  for (const Leaf& leaf : sk.leaves) {
    const auto shape = static_cast<std::size_t>(leaf.shape);
    if (cards_of[shape] == 0) cards_of[shape] = leaf_panels(leaf_outline(shape), o).cards();
    s.leaf_cards += cards_of[shape];
  }
  s.curve_segments += petiole_segments(sk, o);
  s.leaf_outline_triangles = leaf_outline_triangles(sk, o);
  s.leaf_triangles = sk.leaf_triangles.size();
  for (const LeafLine& line : sk.leaf_lines) s.curve_segments += kept_as_line(line) ? 1u : 0u;
  if (o.ramiform) count_ramiforms(sk, limbs, o, s);
  return s;
}

}  // namespace arbor::generator
