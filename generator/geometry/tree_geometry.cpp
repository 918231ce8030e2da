// Building TreeGeometry from a Skeleton: limbs → Hermite curve segments, trunks → displaced grids,
// leaves → triangles.
#include "generator/geometry/tree_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "generator/geometry/geometry_plan.h"
#include "generator/geometry/leaf_cards.h"
#include "generator/geometry/leaf_shapes.h"
#include "generator/geometry/limbs.h"
#include "generator/geometry/ramiform.h"
#include "generator/species.h"
#include "generator/models/weber_penn/weber_penn_formulas.h"
#include "common/math.h"

namespace arbor::generator {

namespace {

template <typename T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

// A Hermite end slope for the radius limited so that the piece's cubic radius stays between its
// end radii (Fritsch & Carlson 1980: slopes of the secant's sign, at most 3 × the secant). The
// finite differences of a law with unbounded slope (periodic taper's joins) would otherwise
// swing the cubic far past the limb (the Saguaro's arms ended in discs 6 times their width).
double monotone_slope(double slope, double secant) {
  if (!std::isfinite(slope) || secant == 0.0 || (slope > 0.0) != (secant > 0.0)) return 0.0;
  return std::fabs(slope) > 3.0 * std::fabs(secant) ? 3.0 * secant : slope;
}

// Embree needs radius < radius of curvature everywhere on a round curve. Returns the largest
// radius × curvature over the segment, checked at 33 cosine-spaced points (dense near the ends,
// where a short clamped tangent makes the curvature peak).
double worst_radius_curvature(const CurveSet& c, std::size_t i) {
  double worst = 0.0;
  for (int k = 0; k <= 32; ++k) {
    const float u = static_cast<float>(0.5 * (1.0 - std::cos(kPi * k / 32.0)));
    const glm::vec4 p = c.position(i, u);
    const glm::dvec3 d1(c.derivative(i, u)), d2(c.second_derivative(i, u));
    const double speed = glm::length(d1);
    if (speed < 1e-12) continue;
    const double curvature = glm::length(glm::cross(d1, d2)) / (speed * speed * speed);
    worst = std::max(worst, static_cast<double>(p.w) * curvature);
  }
  return worst;
}

// The radius a limb can have at t: its own, limited to 90 % of the spline's radius of curvature
// (Embree's rule for round curves). Both are continuous along a C2 spline, so the limit is too.
double allowed_radius(const Skeleton& sk, const Limb& limb, double t) {
  const double r = limb.radius_at(sk, t);
  const double k = limb.spline.curvature(t);
  return k > 0.0 ? std::min(r, 0.9 / k) : r;
}

void add_limb_curves(const Skeleton& sk, const Limb& limb, std::int32_t limb_index,
                     TreeGeometry& g) {
  const CubicSpline& spline = limb.spline;
  std::vector<double> ts;
  std::vector<bool> limited;
  limb_pieces(sk, limb, ts, limited);
  const std::vector<FrameSample> frames =
      rotation_minimizing_frames(spline, ts, limb.knot_normals.front());
  CurveSet& c = g.curves;
  for (std::size_t j = 0; j + 1 < ts.size(); ++j) {
    const double a = ts[j], b = ts[j + 1], h = b - a;
    // The exact sub-segment of the spline: Hermite data are position and dP/dt × h.
    const glm::dvec3 pa = spline.position(a), pb = spline.position(b);
    const glm::dvec3 da = spline.derivative(a) * h, db = spline.derivative(b) * h;
    // Radius at both ends from inside the piece: the law may step at a knot (an L-system's r(n)
    // between stems), and each piece follows its own side of the step. Slopes by one-sided
    // differences inside the piece.
    const double e = 1e-4 * h;
    const double ra = allowed_radius(sk, limb, a), rb = allowed_radius(sk, limb, b - 1e-6 * h);
    const double dra = monotone_slope((allowed_radius(sk, limb, a + e) - ra) / e * h, rb - ra);
    const double drb = monotone_slope((rb - allowed_radius(sk, limb, b - e)) / e * h, rb - ra);
    c.points.emplace_back(glm::vec3(pa), static_cast<float>(ra));
    c.points.emplace_back(glm::vec3(pb), static_cast<float>(rb));
    c.tangents.emplace_back(glm::vec3(da), static_cast<float>(dra));
    c.tangents.emplace_back(glm::vec3(db), static_cast<float>(drb));
    CurveSegment seg;
    seg.limb = limb_index;
    seg.color =
        sk.stems[static_cast<size_t>(
                     limb.knots[std::min(limb.knots.size() - 1, static_cast<std::size_t>(1))].stem)]
            .color;
    double mid_u = 0.0;  // the stem this piece lies on, at its middle
    const std::size_t knot = spline.locate(0.5 * (a + b), mid_u);
    seg.lod_level = static_cast<std::uint8_t>(
        std::min(2, sk.stems[static_cast<std::size_t>(limb.segment_stem(knot))].level));
    seg.arc0 = static_cast<float>(limb.arc_at(a));
    seg.arc1 = static_cast<float>(limb.arc_at(b));
    seg.normal0 = glm::vec3(frames[j].normal);
    seg.normal1 = glm::vec3(frames[j + 1].normal);
    c.segments.push_back(seg);
    const std::size_t i = c.segments.size() - 1;
    if (limited[j]) ++g.stats.radius_adjusted_segments;
    const double worst = worst_radius_curvature(c, i);
    if (worst >= 0.98) {
      // Last resort (float rounding of a piece already limited): thin it linearly in u.
      const float scale = static_cast<float>(0.9 / worst);
      c.points[2 * i].w *= scale;
      c.points[2 * i + 1].w *= scale;
      c.tangents[2 * i].w = c.tangents[2 * i + 1].w = c.points[2 * i + 1].w - c.points[2 * i].w;
      ++g.stats.radius_adjusted_segments;
    }
  }
}

// Root buttresses (Bloomenthal 1985, the base of a tree: "planar blobby" contours, after Blinn,
// around the points where the roots cross each plane). In the ring `h` metres up the trunk, below
// H = buttress_height × the base radius R, root k crosses the plane at distance
// R (0.6 + spread s²) in direction φ_k (s = 1 - h/H rising smoothly to 1 at the ground, φ_k evenly
// spaced with a fixed jitter), as a blob of radius R (0.35 + 0.25 s) and weight s. The contour is
// the equipotential F = 1/e of F(p) = exp(-(|p|/ρ0)²) + Σ s exp(-|p - c_k|²/σ²), ρ0 the trunk's
// own contour (flare and lobes): without roots exactly ρ0, with them never inside it, merging
// smoothly into the trunk at H. Returns the contour's radius in direction θ: the outermost
// crossing along the ray, so the ring stays star-shaped about the axis.
double buttress_contour(const GeometryOptions& o, double base_radius, double h, double theta,
                        double rho0) {
  const double height = o.buttress_height * base_radius;
  if (o.buttresses <= 0 || h >= height) return rho0;
  const double e = 1.0 - h / height;
  const double s = e * e * (3.0 - 2.0 * e);
  const double reach = base_radius * (0.6 + o.buttress_spread * s * s);
  const double sigma = base_radius * (0.35 + 0.25 * s);
  const double threshold = std::exp(-1.0);
  // The roots' crossing points in this plane (at most 16), found once for the search below.
  std::array<glm::dvec2, 16> roots{};
  const int n = std::min(o.buttresses, static_cast<int>(roots.size()));
  for (int k = 0; k < n; ++k) {
    const double jitter = 0.35 * (std::fmod(0.618034 * (k + 1), 1.0) - 0.5);
    const double phi = 2.0 * kPi * (k + jitter) / o.buttresses;
    roots[static_cast<std::size_t>(k)] = {reach * std::cos(phi), reach * std::sin(phi)};
  }
  const double ct = std::cos(theta), st = std::sin(theta);
  auto field = [&](double rho) {
    double f = std::exp(-(rho / rho0) * (rho / rho0));
    for (int k = 0; k < n; ++k) {
      const glm::dvec2 c = roots[static_cast<std::size_t>(k)];
      const double dx = rho * ct - c.x, dy = rho * st - c.y;
      f += s * std::exp(-(dx * dx + dy * dy) / (sigma * sigma));
    }
    return f;
  };
  const double far = rho0 + reach + 3.0 * sigma;
  const int steps = 64;
  double lo = rho0, hi = far;
  for (int i = steps - 1; i >= 0; --i) {  // from outside in: the first point inside the contour
    const double rho = rho0 + (far - rho0) * i / steps;
    if (field(rho) >= threshold) {
      lo = rho;
      hi = rho0 + (far - rho0) * (i + 1) / steps;
      break;
    }
  }
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (field(mid) >= threshold ? lo : hi) = mid;
  }
  return lo;
}

// Weber & Penn §4.4 flare and lobes as real displacement of a trunk limb's surface.
void add_trunk_grid(const Skeleton& sk, const Limb& limb, std::int32_t limb_index,
                    const GeometryOptions& o, TreeGeometry& g) {
  const CubicSpline& spline = limb.spline;
  const double base_radius = limb.radius_at(sk, 0.0);
  const std::vector<double> ts = grid_rings(sk, limb, o);
  const int sides = grid_sides(sk, o);
  const std::vector<FrameSample> frames =
      rotation_minimizing_frames(spline, ts, limb.knot_normals.front());
  GridSet& gs = g.grids;
  DisplacedGrid grid;
  grid.first_vertex = static_cast<std::uint32_t>(gs.vertices.size());
  grid.width = static_cast<std::uint16_t>(sides + 1);
  grid.height = static_cast<std::uint16_t>(ts.size());
  grid.limb = limb_index;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    const glm::dvec3 centre = spline.position(ts[i]);
    const glm::dvec3 n = frames[i].normal, b = glm::cross(frames[i].tangent, frames[i].normal);
    const double z = limb.z_at(sk, ts[i]);
    const double r = limb.radius_at(sk, ts[i]);
    const double flare = wp::flare_scale(sk.trunk.flare, z);
    const double arc = limb.arc_at(ts[i]);
    for (int j = 0; j <= sides; ++j) {
      const double angle = 2.0 * kPi * j / sides;
      const double lobe = wp::lobe_scale(sk.trunk.lobes, sk.trunk.lobe_depth, angle);
      const glm::dvec3 radial = n * std::cos(angle) + b * std::sin(angle);
      const double rho = buttress_contour(o, base_radius, arc, angle, r * flare * lobe);
      gs.vertices.emplace_back(centre + radial * rho);
      gs.bark.emplace_back(static_cast<float>(arc), static_cast<float>(r * angle));
    }
  }
  // Shading normals of the displaced surface from its own finite differences, facing outward.
  const std::size_t w = grid.width, h = grid.height, first = grid.first_vertex;
  auto at = [&](std::size_t i, std::size_t j) {
    return glm::dvec3(gs.vertices[first + i * w + j]);
  };
  for (std::size_t i = 0; i < h; ++i) {
    for (std::size_t j = 0; j < w; ++j) {
      const std::size_t jl = j == 0 ? w - 2 : j - 1, jr = j + 1 == w ? 1 : j + 1;
      const std::size_t iu = std::min(h - 1, i + 1), id = i == 0 ? 0 : i - 1;
      const glm::dvec3 around = at(i, jr) - at(i, jl);
      glm::dvec3 along = at(iu, j) - at(id, j);
      if (glm::length(along) < 1e-12) along = frames[i].tangent;
      glm::dvec3 normal = glm::cross(around, along);
      const glm::dvec3 radial = at(i, j) - spline.position(ts[i]);
      if (glm::dot(normal, radial) < 0.0) normal = -normal;
      if (glm::length(normal) > 1e-20) {
        gs.normals.emplace_back(glm::normalize(normal));
      } else {
        // A ring of radius 0 (the tip of a trunk tapered to a point) has no surface direction
        // of its own: it takes the frame's outward direction of its column.
        const double angle = 2.0 * kPi * static_cast<double>(j) / static_cast<double>(sides);
        gs.normals.emplace_back(frames[i].normal * std::cos(angle) +
                                glm::cross(frames[i].tangent, frames[i].normal) * std::sin(angle));
      }
    }
  }
  gs.grids.push_back(grid);
}

void add_free_leaves(const Skeleton& sk, TreeGeometry& g) {
  LeafMesh& m = g.leaves;
  // Free-form elements (TREE-MAKER): triangles as they are, uv over their own corners.
  for (const LeafTriangle& tri : sk.leaf_triangles) {
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 3; ++k) m.positions.push_back(tri.v[k]);
    m.uvs.insert(m.uvs.end(), {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1)});
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2});
    m.front_material.push_back(kMaterialLeafFront);
    m.back_material.push_back(kMaterialLeafBack);
    m.leaf.push_back(-1);
    m.color.push_back(tri.color);
  }
}

// Lines of leaves (TREE-MAKER's ln=) as thin straight limbs of constant radius.
void add_leaf_lines(const Skeleton& sk, TreeGeometry& g) {
  for (const LeafLine& l : sk.leaf_lines) {
    const glm::vec3 d = l.b - l.a;
    if (!kept_as_line(l)) continue;
    CurveSet& c = g.curves;
    c.points.emplace_back(l.a, l.radius);
    c.points.emplace_back(l.b, l.radius);
    c.tangents.emplace_back(d, 0.0f);
    c.tangents.emplace_back(d, 0.0f);
    CurveSegment seg;
    seg.limb = -1;
    seg.lod_level = kNoLod;
    seg.arc0 = 0.0f;
    seg.arc1 = glm::length(d);
    const glm::vec3 n = glm::normalize(glm::cross(
        d, std::fabs(d.z) < 0.9f * glm::length(d) ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0)));
    seg.normal0 = seg.normal1 = n;
    seg.color = l.color;
    c.segments.push_back(seg);
  }
}

// Each curve segment's index among its level's (level of detail, scene/lod.h), and the shaped
// leaves' count.
void number_lod_items(TreeGeometry& g) {
  g.lod_items = {};
  for (CurveSegment& seg : g.curves.segments) {
    // Petioles (level 3) carry their leaf's index already: they go with their leaf.
    if (seg.lod_level < 3) seg.lod_item = g.lod_items[seg.lod_level]++;
  }
  for (const LeafCard& c : g.cards.cards)
    g.lod_items[3] = std::max(g.lod_items[3], static_cast<std::uint32_t>(c.leaf) + 1);
}

void finish(TreeGeometry& g) {
  GeometryStats& s = g.stats;
  s.curve_segments = g.curves.size();
  s.grids = g.grids.grids.size();
  s.grid_vertices = g.grids.vertices.size();
  s.grid_triangles = 0;
  for (const DisplacedGrid& d : g.grids.grids) {
    s.grid_triangles += 2u * (d.width - 1u) * (d.height - 1u);
  }
  s.leaf_triangles = g.leaves.triangle_count();
  s.leaf_cards = g.cards.size();
  s.ramiforms = g.ramiforms.forks.size();
  s.ramiform_triangles = g.ramiforms.triangle_count();
  s.bytes = bytes_of(g.curves.points) + bytes_of(g.curves.tangents) + bytes_of(g.curves.segments) +
            bytes_of(g.grids.vertices) + bytes_of(g.grids.normals) + bytes_of(g.grids.bark) +
            bytes_of(g.grids.grids) + bytes_of(g.leaves.positions) + bytes_of(g.leaves.uvs) +
            bytes_of(g.leaves.indices) + bytes_of(g.leaves.front_material) +
            bytes_of(g.leaves.back_material) + bytes_of(g.leaves.leaf) + bytes_of(g.leaves.color) +
            bytes_of(g.cards.corners) + bytes_of(g.cards.cards) + bytes_of(g.ramiforms.positions) +
            bytes_of(g.ramiforms.normals) + bytes_of(g.ramiforms.tangents) +
            bytes_of(g.ramiforms.bark) + bytes_of(g.ramiforms.indices) +
            bytes_of(g.ramiforms.forks);
  bool any = false;
  auto grow = [&](const glm::vec3& p, float r) {
    if (!any) {
      g.bounds_min = p - r;
      g.bounds_max = p + r;
      any = true;
    }
    g.bounds_min = glm::min(g.bounds_min, p - r);
    g.bounds_max = glm::max(g.bounds_max, p + r);
  };
  for (std::size_t i = 0; i < g.curves.size(); ++i) {
    // A Hermite segment lies within the hull of its Bézier control points.
    const glm::vec4 p0 = g.curves.points[2 * i], p1 = g.curves.points[2 * i + 1];
    const glm::vec4 m0 = g.curves.tangents[2 * i], m1 = g.curves.tangents[2 * i + 1];
    const float r = std::max({p0.w, p1.w, p0.w + m0.w / 3.0f, p1.w - m1.w / 3.0f});
    for (const glm::vec4& q : {p0, p1, p0 + m0 / 3.0f, p1 - m1 / 3.0f}) grow(glm::vec3(q), r);
  }
  for (const glm::vec3& v : g.grids.vertices) grow(v, 0.0f);
  for (const glm::vec3& v : g.leaves.positions) grow(v, 0.0f);
  for (const glm::vec3& v : g.cards.corners) grow(v, 0.0f);
  for (const glm::vec3& v : g.ramiforms.positions) grow(v, 0.0f);
}

}  // namespace

glm::vec4 CurveSet::position(std::size_t i, float u) const {
  const float u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * points[2 * i] + (u3 - 2 * u2 + u) * tangents[2 * i] +
         (-2 * u3 + 3 * u2) * points[2 * i + 1] + (u3 - u2) * tangents[2 * i + 1];
}

glm::vec4 CurveSet::derivative(std::size_t i, float u) const {
  const float u2 = u * u;
  return (6 * u2 - 6 * u) * points[2 * i] + (3 * u2 - 4 * u + 1) * tangents[2 * i] +
         (-6 * u2 + 6 * u) * points[2 * i + 1] + (3 * u2 - 2 * u) * tangents[2 * i + 1];
}

glm::vec4 CurveSet::second_derivative(std::size_t i, float u) const {
  return (12 * u - 6) * points[2 * i] + (6 * u - 4) * tangents[2 * i] +
         (-12 * u + 6) * points[2 * i + 1] + (6 * u - 2) * tangents[2 * i + 1];
}

namespace {

// Every limb as its round curve or, for a flared or lobed trunk, its displaced grid.
void add_limbs(const Skeleton& sk, const std::vector<Limb>& limbs, const GeometryOptions& o,
               TreeGeometry& g) {
  g.stats.limbs = limbs.size();
  for (const Limb& l : limbs) g.stats.tension_raised_limbs += l.tension_raised ? 1u : 0u;
  for (std::size_t i = 0; i < limbs.size(); ++i) {
    const auto index = static_cast<std::int32_t>(i);
    if (displaced(sk, limbs[i], o)) {
      add_trunk_grid(sk, limbs[i], index, o, g);
    } else {
      add_limb_curves(sk, limbs[i], index, g);
    }
  }
}

}  // namespace

void count_ramiforms(const Skeleton& sk, const std::vector<Limb>& limbs, const GeometryOptions& o,
                     GeometryStats& s) {
  TreeGeometry g;
  add_limbs(sk, limbs, o, g);
  add_ramiforms(limbs, g);
  s.ramiform_forks = g.stats.ramiform_forks;
  s.ramiforms = g.stats.ramiforms;
  s.ramiform_triangles = g.stats.ramiform_triangles;
  s.ramiforms_skipped = g.stats.ramiforms_skipped;
  s.ramiform_trunk_forks = g.stats.ramiform_trunk_forks;
  s.ramiform_trunk_collars = g.stats.ramiform_trunk_collars;
}

TreeGeometry build_tree_geometry(const Skeleton& sk, const GeometryOptions& o) {
  TreeGeometry g;
  const std::vector<Limb> limbs = fit_limbs(sk);
  add_limbs(sk, limbs, o, g);
  add_leaf_cards(sk, o, g);
  add_free_leaves(sk, g);
  add_leaf_lines(sk, g);
  number_lod_items(g);
  if (o.ramiform) add_ramiforms(limbs, g);
  sink_trunk(sk, o.sink_slope, g);
  finish(g);
  g.stats.leaf_outline_triangles = leaf_outline_triangles(sk, o);
  return g;
}

GeometryOptions geometry_options_for(const Species& species) {
  GeometryOptions o;
  if (species.leaf.hinge_angle > 0.0) {
    o.leaf_style = LeafStyle::Hinged;
    o.hinge_angle = species.leaf.hinge_angle;
  }
  const LeafLook& leaf = species.leaf;
  o.leaf_bend = LeafBend::from_degrees(leaf.fold, leaf.cup, leaf.curl, leaf.twist);
  if (!o.leaf_bend.flat()) o.leaf_style = LeafStyle::Shaped;
  o.petiole_length = leaf.petiole_length;
  o.petiole_width = leaf.petiole_width;
  o.leaf_margin = leaf.margin;
  o.buttresses = species.roots.buttresses;
  o.buttress_height = species.roots.height;
  o.buttress_spread = species.roots.spread;
  o.ramiform = species.bark.ramiform;
  return o;
}

BarkCoordinates curve_bark(const CurveSet& c, std::size_t i, float u, const glm::vec3& point) {
  const glm::vec4 p = c.position(i, u);
  const glm::vec3 tangent = glm::normalize(glm::vec3(c.derivative(i, u)));
  const CurveSegment& s = c.segments[i];
  glm::vec3 n = s.normal0 + (s.normal1 - s.normal0) * u;
  n = glm::normalize(n - tangent * glm::dot(n, tangent));
  const glm::vec3 b = glm::cross(tangent, n);
  const glm::vec3 d = point - glm::vec3(p);
  float azimuth = std::atan2(glm::dot(d, b), glm::dot(d, n));
  if (azimuth < 0.0f) azimuth += 2.0f * static_cast<float>(kPi);
  BarkCoordinates bc;
  bc.along = s.arc0 + (s.arc1 - s.arc0) * u;
  bc.around = p.w * azimuth;
  bc.azimuth = azimuth;
  bc.radius = p.w;
  return bc;
}

namespace {
// Bilinear interpolation of a per-vertex attribute over a grid at Embree's grid-wide (u, v).
template <typename T>
T grid_lerp(const std::vector<T>& values, const DisplacedGrid& d, float u, float v) {
  const float x = std::clamp(u, 0.0f, 1.0f) * (d.width - 1),
              y = std::clamp(v, 0.0f, 1.0f) * (d.height - 1);
  const auto i = std::min(static_cast<std::uint32_t>(x), d.width - 2u);
  const auto j = std::min(static_cast<std::uint32_t>(y), d.height - 2u);
  const float fx = x - i, fy = y - j;
  const std::size_t base = d.first_vertex + j * d.width + i;
  const T a = values[base], b = values[base + 1], c = values[base + d.width],
          e = values[base + d.width + 1];
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + e * fx) * fy;
}
}  // namespace

BarkCoordinates grid_bark(const GridSet& g, std::size_t grid, float u, float v) {
  const DisplacedGrid& d = g.grids[grid];
  const glm::vec2 b = grid_lerp(g.bark, d, u, v);
  BarkCoordinates bc;
  bc.along = b.x;
  bc.around = b.y;
  bc.azimuth = 2.0f * static_cast<float>(kPi) * std::clamp(u, 0.0f, 1.0f);
  // around = radius × azimuth at every vertex: recover the radius from the row's last column.
  const float row_end = grid_lerp(g.bark, d, 1.0f, v).y;
  bc.radius = row_end / (2.0f * static_cast<float>(kPi));
  return bc;
}

glm::vec3 grid_normal(const GridSet& g, std::size_t grid, float u, float v) {
  return glm::normalize(grid_lerp(g.normals, g.grids[grid], u, v));
}

}  // namespace arbor::generator
