// The two limb surfaces a ramiform's collar joins (generator/geometry/ramiform.h), as the
// renderer draws them: a parent limb's round curve or displaced grid, with inside tests, depths
// and projections onto it, and a child limb's round curve by (τ, φ). Used by ramiform.cpp only.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "generator/geometry/limbs.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::generator::ramiform_detail {

// A point of a rendered limb surface, with what the renderer computes for a hit there.
struct SurfaceSample {
  glm::dvec3 position{0.0}, normal{0.0}, tangent{0.0};
  glm::dvec3 bark{0.0};  // along, azimuth, radius
  bool cap = false;      // on a round curve's joint, where Embree draws no surface
};

// The surface of a parent limb: inside tests and projections onto it along the direction from
// its axis, for a round curve (the sphere sweep Embree renders) or a displaced grid.
class ParentSurface {
 public:
  ParentSurface(const TreeGeometry& g, std::int32_t limb) : g_(g) {
    for (std::size_t i = 0; i < g.curves.size(); ++i)
      if (g.curves.segments[i].limb == limb) segments_.push_back(i);
    // Each segment's coarse axis points, once, and the sphere about them (a lower bound on the
    // distance to any of them), so a projection measures only the segments that can be nearest.
    for (std::size_t i : segments_) {
      Coarse k;
      glm::dvec3 mean(0.0);
      for (int j = 0; j <= kCoarse; ++j) {
        k.points[j] = glm::dvec3(glm::vec3(g.curves.position(i, static_cast<float>(j / 16.0))));
        mean += k.points[j];
      }
      k.centre = mean / double(kCoarse + 1);
      for (const glm::dvec3& q : k.points) k.reach = std::max(k.reach, glm::length(q - k.centre));
      coarse_.push_back(k);
    }
    for (std::size_t i = 0; i < g.grids.grids.size(); ++i)
      if (g.grids.grids[i].limb == limb) grid_ = i;
    if (grid_) {
      const DisplacedGrid& d = g.grids.grids[*grid_];
      for (std::uint32_t row = 0; row < d.height; ++row) {
        glm::dvec3 sum(0.0);
        for (std::uint32_t col = 0; col + 1 < d.width; ++col) sum += vertex(row, col);
        centres_.push_back(sum / static_cast<double>(d.width - 1));
      }
      // Each ring's frame: toward its first column and a quarter turn on (columns are at equal
      // azimuths of the trunk's frame, displaced along them), to find a direction's column.
      for (std::uint32_t row = 0; row < d.height; ++row) {
        const glm::dvec3 t = centres_[std::min<std::uint32_t>(row + 1, d.height - 1)] -
                             centres_[row > 0 ? row - 1 : 0];
        glm::dvec3 n = vertex(row, 0) - centres_[row];
        n -= t * (glm::dot(n, t) / std::max(1e-300, glm::dot(t, t)));
        glm::dvec3 b = glm::cross(t, n);
        if (glm::dot(b, vertex(row, (d.width - 1) / 4) - centres_[row]) < 0.0) b = -b;
        const bool ok = glm::length(n) > 1e-12 && glm::length(b) > 1e-12;
        frames_.push_back(
            {ok ? glm::normalize(n) : glm::dvec3(0.0), ok ? glm::normalize(b) : glm::dvec3(0.0)});
      }
    }
  }
  bool valid() const { return grid_ || !segments_.empty(); }

  // How deep p lies inside the surface on the way from the axis through it (negative outside);
  // none where that way meets no surface. For a round curve it is p's depth in a sphere of the
  // sweep, so the ball of that radius about p lies inside.
  std::optional<double> depth(const glm::dvec3& p) const {
    const std::optional<SurfaceSample> s = project(p);
    if (!s) return std::nullopt;
    return glm::length(s->position - axis_) - glm::length(p - axis_);
  }
  // Whether p lies inside the surface.
  bool inside(const glm::dvec3& p) const {
    const std::optional<double> d = depth(p);
    return d && *d > 0.0;
  }
  bool round() const { return !grid_; }

  // The surface point on the way from the axis through p.
  std::optional<SurfaceSample> project(const glm::dvec3& p) const {
    return grid_ ? project_on_grid(p) : project_on_curve(p);
  }

 private:
  glm::dvec3 vertex(std::uint32_t row, std::uint32_t col) const {
    const DisplacedGrid& d = g_.grids.grids[*grid_];
    return glm::dvec3(g_.grids.vertices[d.first_vertex + row * d.width + col]);
  }

  // The parameter of segment i's axis point nearest p, from its coarse point k nearest p: Newton's
  // method on the distance's derivative g(u) = (c(u) − p)·c'(u), kept inside the bracket of k's
  // neighbours where g changes sign (bisection when a step leaves it); an end of the segment when
  // g does not change sign there (the distance grows from it).
  double nearest_on_segment(const glm::dvec3& p, std::size_t i, int k) const {
    const CurveSet& c = g_.curves;
    const auto g = [&](double u) {
      const auto f = static_cast<float>(u);
      return glm::dot(glm::dvec3(glm::vec3(c.position(i, f))) - p,
                      glm::dvec3(glm::vec3(c.derivative(i, f))));
    };
    double lo = std::max(0, k - 1) / double(kCoarse),
           hi = std::min(kCoarse, k + 1) / double(kCoarse);
    const double g_lo = g(lo), g_hi = g(hi);
    if (g_lo >= 0.0 && lo == 0.0 && g_hi > 0.0) return 0.0;
    if (g_hi <= 0.0 && hi == 1.0 && g_lo < 0.0) return 1.0;
    if (g_lo >= 0.0 || g_hi <= 0.0) return golden_section(p, i, lo, hi);  // not convex here
    double u = std::clamp(k / double(kCoarse), lo, hi);
    for (int step = 0; step < 40 && hi - lo > 1e-7; ++step) {
      const auto f = static_cast<float>(u);
      const glm::dvec3 to = glm::dvec3(glm::vec3(c.position(i, f))) - p;
      const glm::dvec3 d1(glm::vec3(c.derivative(i, f))), d2(glm::vec3(c.second_derivative(i, f)));
      const double gu = glm::dot(to, d1), slope = glm::dot(d1, d1) + glm::dot(to, d2);
      (gu < 0.0 ? lo : hi) = u;
      const double next = slope > 0.0 ? u - gu / slope : 0.5 * (lo + hi);
      const double v = next > lo && next < hi ? next : 0.5 * (lo + hi);
      if (std::fabs(v - u) < 1e-7) return v;
      u = v;
    }
    return u;
  }

  // The distance's minimum on [a0, b0] by golden-section search: each step keeps one of its two
  // inner points (at the exact ratio they coincide), so it measures one new distance a step.
  double golden_section(const glm::dvec3& p, std::size_t i, double a0, double b0) const {
    const auto distance = [&](double u) {
      return glm::length(p - glm::dvec3(glm::vec3(g_.curves.position(i, static_cast<float>(u)))));
    };
    constexpr double kRatio = 0.6180339887498949;  // (√5 − 1) / 2
    double a = b0 - kRatio * (b0 - a0), b = a0 + kRatio * (b0 - a0);
    double da = distance(a), db = distance(b);
    for (int k = 0; k < 28; ++k) {
      if (da < db) {
        b0 = b;
        b = a, db = da;
        a = b0 - kRatio * (b0 - a0), da = distance(a);
      } else {
        a0 = a;
        a = b, da = db;
        b = a0 + kRatio * (b0 - a0), db = distance(b);
      }
    }
    return 0.5 * (a0 + b0);
  }

  // Embree's round curve is each segment's sweep of spheres without caps at the joints: a point
  // belongs to a segment where its nearest axis point is inside the segment (u in (0, 1)). So the
  // projection is onto the segment whose inside nearest point is nearest the surface.
  std::optional<SurfaceSample> project_on_curve(const glm::dvec3& p) const {
    const CurveSet& c = g_.curves;
    const auto distance = [&](std::size_t i, double u) {
      return glm::length(p - glm::dvec3(glm::vec3(c.position(i, static_cast<float>(u)))));
    };
    // The three segments whose coarse axis points come nearest p (ties by index): measured in
    // the order of their spheres' lower bounds, until no bound is below the third nearest yet
    // (the same three, and the same distances, as measuring every segment).
    std::vector<std::pair<double, std::size_t>>& bounds =
        bounds_;  // (lower bound, segments_ index)
    bounds.clear();
    for (std::size_t n = 0; n < segments_.size(); ++n)
      bounds.emplace_back(glm::length(p - coarse_[n].centre) - coarse_[n].reach - 1e-9, n);
    std::sort(bounds.begin(), bounds.end());
    std::vector<Near>& near = near_;
    near.clear();
    for (const auto& [bound, n] : bounds) {
      if (near.size() >= 3) {
        std::nth_element(near.begin(), near.begin() + 2, near.end());
        if (bound > near[2].distance) break;
      }
      Near m{1e300, segments_[n], 0};
      for (int k = 0; k <= kCoarse; ++k) {
        const glm::dvec3 e = p - coarse_[n].points[k];
        const double d2 = glm::dot(e, e);  // squared: one square root per segment
        if (d2 < m.distance) m.distance = d2, m.coarse = k;
      }
      m.distance = std::sqrt(m.distance);
      near.push_back(m);
    }
    std::sort(near.begin(), near.end());
    double best = 1e300, best_u = 0.0;
    bool cap = false;
    std::size_t best_seg = 0;
    for (std::size_t n = 0; n < std::min<std::size_t>(3, near.size()); ++n) {
      const std::size_t i = near[n].segment;
      const double u = nearest_on_segment(p, i, near[n].coarse);
      // Beyond this segment's own sweep: a joint, counted only when no segment has p inside.
      const bool joint = u < 1e-3 || u > 1.0 - 1e-3;
      const double gap =
          distance(i, u) - c.position(i, static_cast<float>(u)).w + (joint ? 1e-9 : 0.0);
      if (gap < best) best = gap, best_seg = i, best_u = u, cap = joint;
    }
    if (best == 1e300) return std::nullopt;
    const auto u = static_cast<float>(best_u);
    const glm::vec4 a = c.position(best_seg, u);
    axis_ = glm::dvec3(glm::vec3(a));
    const glm::dvec3 out = p - axis_;
    if (glm::length(out) < 1e-12) return std::nullopt;
    SurfaceSample s;
    s.normal = glm::normalize(out);
    s.position = axis_ + s.normal * static_cast<double>(a.w);
    s.tangent = glm::normalize(glm::dvec3(glm::vec3(c.derivative(best_seg, u))));
    const BarkCoordinates bc = curve_bark(c, best_seg, u, glm::vec3(s.position));
    s.bark = {bc.along, bc.azimuth, bc.radius};
    s.cap = cap;
    return s;
  }

  // The nearest hit of the ray from axis_ along dir with column col's quads of the rows within
  // six of `row`, into `hit` (t, and the grid's u and v there) when nearer than it.
  struct GridHit {
    double t = 1e300, u = 0.0, v = 0.0;
  };
  void hit_cell(const glm::dvec3& dir, std::uint32_t col, std::size_t row, GridHit& hit) const {
    const DisplacedGrid& d = g_.grids.grids[*grid_];
    const std::uint32_t r0 = row > 6 ? static_cast<std::uint32_t>(row) - 6 : 0;
    const std::uint32_t r1 =
        std::min<std::uint32_t>(d.height - 1, static_cast<std::uint32_t>(row) + 7);
    for (std::uint32_t r = r0; r < r1; ++r) {
      const glm::dvec3 v0 = vertex(r, col), v1 = vertex(r, col + 1), v2 = vertex(r + 1, col + 1),
                       v3 = vertex(r + 1, col);
      // Embree's two triangles of a grid quad: (v0, v1, v3) and (v2, v3, v1).
      for (int half = 0; half < 2; ++half) {
        const glm::dvec3 a = half ? v2 : v0, b = half ? v3 : v1, c = half ? v1 : v3;
        const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(dir, e2);
        const double det = glm::dot(e1, q);
        if (std::fabs(det) < 1e-30) continue;
        const glm::dvec3 s = axis_ - a;
        const double bu = glm::dot(s, q) / det;
        const glm::dvec3 rr = glm::cross(s, e1);
        const double bv = glm::dot(dir, rr) / det;
        const double t = glm::dot(e2, rr) / det;
        if (bu < -1e-9 || bv < -1e-9 || bu + bv > 1 + 1e-9 || t <= 0 || t >= hit.t) continue;
        hit.t = t;
        const double fx = half ? 1.0 - bu : bu, fy = half ? 1.0 - bv : bv;
        hit.u = (col + fx) / (d.width - 1.0);
        hit.v = (r + fy) / (d.height - 1.0);
      }
    }
  }

  std::optional<SurfaceSample> project_on_grid(const glm::dvec3& p) const {
    // The nearest point of the rings' centres' polyline, and the ray from it through p.
    double best = 1e300, f_best = 0.0;
    std::size_t row = 0;
    for (std::size_t i = 0; i + 1 < centres_.size(); ++i) {
      const glm::dvec3 e = centres_[i + 1] - centres_[i];
      const double len2 = glm::dot(e, e);
      const double f = len2 > 0 ? std::clamp(glm::dot(p - centres_[i], e) / len2, 0.0, 1.0) : 0.0;
      const glm::dvec3 to = p - (centres_[i] + f * e);
      const double d2 = glm::dot(to, to);
      if (d2 < best) best = d2, f_best = f, row = i;
    }
    axis_ = centres_[row] + f_best * (centres_[row + 1] - centres_[row]);
    const glm::dvec3 out = p - axis_;
    if (glm::length(out) < 1e-12) return std::nullopt;
    const glm::dvec3 dir = glm::normalize(out);
    const DisplacedGrid& d = g_.grids.grids[*grid_];
    // The columns within three of the direction's azimuth first (a ray from the axis meets the
    // star-shaped ring there), all of them when those miss.
    const std::uint32_t sides = d.width - 1u;
    const std::array<glm::dvec3, 2>& f = frames_[row];
    GridHit hit;
    if (glm::length(f[0]) > 0.0) {
      double turn = std::atan2(glm::dot(dir, f[1]), glm::dot(dir, f[0])) / (2.0 * kPi);
      if (turn < 0.0) turn += 1.0;
      const auto centre_col = static_cast<std::int64_t>(turn * sides);
      for (std::int64_t k = -3; k <= 3; ++k)
        hit_cell(dir, static_cast<std::uint32_t>((centre_col + k + 2 * sides) % sides), row, hit);
    }
    if (hit.t == 1e300)
      for (std::uint32_t col = 0; col < sides; ++col) hit_cell(dir, col, row, hit);
    const double t_hit = hit.t, gu = hit.u, gv = hit.v;
    if (t_hit == 1e300) return std::nullopt;
    SurfaceSample s;
    s.position = axis_ + dir * t_hit;
    const auto fu = static_cast<float>(gu), fv = static_cast<float>(gv);
    s.normal = glm::dvec3(grid_normal(g_.grids, *grid_, fu, fv));
    if (glm::dot(s.normal, dir) < 0.0) s.normal = -s.normal;
    s.tangent = glm::normalize(centres_[row + 1] - centres_[row]);
    const BarkCoordinates bc = grid_bark(g_.grids, *grid_, fu, fv);
    s.bark = {bc.along, bc.azimuth, bc.radius};
    return s;
  }

  const TreeGeometry& g_;
  std::vector<std::size_t> segments_;
  static constexpr int kCoarse = 16;  // a segment's coarse axis points: u = 0, 1/16, …, 1
  struct Coarse {
    std::array<glm::dvec3, kCoarse + 1> points{};
    glm::dvec3 centre{0.0};
    double reach = 0.0;
  };
  std::vector<Coarse> coarse_;  // by segments_
  // A segment among the nearest: its coarse distance and coarse point (scratch of projections).
  struct Near {
    double distance;
    std::size_t segment;
    int coarse;
    bool operator<(const Near& o) const {
      return distance < o.distance || (distance == o.distance && segment < o.segment);
    }
  };
  mutable std::vector<std::pair<double, std::size_t>> bounds_;
  mutable std::vector<Near> near_;
  std::optional<std::size_t> grid_;
  std::vector<glm::dvec3> centres_;
  std::vector<std::array<glm::dvec3, 2>> frames_;  // by row: toward column 0, a quarter on
  mutable glm::dvec3 axis_{0.0};                   // the axis point of the last projection
};

// A child limb's round curve, by τ (segment index + u along its segments from its base) and the
// azimuth φ about its frame: the sphere sweep's surface point whose normal has azimuth φ.
class ChildSurface {
 public:
  ChildSurface(const CurveSet& c, std::int32_t limb) : c_(c) {
    for (std::size_t i = 0; i < c.size(); ++i)
      if (c.segments[i].limb == limb) segments_.push_back(i);
  }
  double end() const { return static_cast<double>(segments_.size()); }
  std::size_t first() const { return segments_.front(); }

  SurfaceSample at(double tau, double phi) const {
    const std::size_t k = std::min(segments_.size() - 1, static_cast<std::size_t>(tau));
    const std::size_t i = segments_[k];
    const auto u = static_cast<float>(std::clamp(tau - static_cast<double>(k), 0.0, 1.0));
    const glm::vec4 p = c_.position(i, u), dp = c_.derivative(i, u);
    const glm::dvec3 axis{glm::vec3(p)};
    const glm::dvec3 t = glm::normalize(glm::dvec3(glm::vec3(dp)));
    const CurveSegment& s = c_.segments[i];
    glm::dvec3 n = glm::dvec3(s.normal0 + (s.normal1 - s.normal0) * u);
    n = glm::normalize(n - t * glm::dot(n, t));
    const glm::dvec3 b = glm::cross(t, n);
    const glm::dvec3 w = n * std::cos(phi) + b * std::sin(phi);
    // The sweep's normal leans back by the radius' slope along the axis.
    const double slope = std::clamp(dp.w / glm::length(glm::vec3(dp)), -0.9f, 0.9f);
    SurfaceSample out;
    out.normal = w * std::sqrt(1.0 - slope * slope) - t * slope;
    out.position = axis + out.normal * static_cast<double>(p.w);
    out.tangent = t;
    const BarkCoordinates bc = curve_bark(c_, i, u, glm::vec3(out.position));
    out.bark = {bc.along, bc.azimuth, bc.radius};
    return out;
  }
  double radius(double tau) const {
    const std::size_t k = std::min(segments_.size() - 1, static_cast<std::size_t>(tau));
    return c_.position(segments_[k], static_cast<float>(std::clamp(tau - k, 0.0, 1.0))).w;
  }
  // Whether the surface point at (τ, φ) lies inside a nearby sphere of the sweep (on the inside
  // of a bend, where the tube overlaps itself and its surface is elsewhere).
  bool hides(double tau, double phi) const {
    const double r = radius(tau), reach = 2.0 * r * per_metre(tau);
    const glm::dvec3 s = at(tau, phi).position;
    for (int i = -20; i <= 20; ++i) {
      const double t = std::clamp(tau + reach * i / 20.0, 0.0, end() - 1e-9);
      const std::size_t seg = std::min(segments_.size() - 1, static_cast<std::size_t>(t));
      const glm::vec4 c = c_.position(segments_[seg], static_cast<float>(t - seg));
      if (glm::length(s - glm::dvec3(glm::vec3(c))) < c.w - 0.005 * r) return true;
    }
    return false;
  }
  // τ per metre of axis near τ.
  double per_metre(double tau) const {
    const std::size_t k = std::min(segments_.size() - 1, static_cast<std::size_t>(tau));
    const float u = static_cast<float>(std::clamp(tau - k, 0.0, 1.0));
    return 1.0 / std::max(1e-9f, glm::length(glm::vec3(c_.derivative(segments_[k], u))));
  }

 private:
  const CurveSet& c_;
  std::vector<std::size_t> segments_;
};

}  // namespace arbor::generator::ramiform_detail
