// The ramiform's collars: the parent's and the child's rendered surfaces as functions, the
// child's footprint on the parent, the two rings, and the Hermite columns between them.
#include "generator/geometry/ramiform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "generator/geometry/ramiform_surfaces.h"

namespace arbor::generator {

namespace {

using ramiform_detail::ChildSurface;
using ramiform_detail::ParentSurface;
using ramiform_detail::SurfaceSample;

constexpr std::uint32_t kSides = kRamiformSides, kRows = kRamiformRows;
constexpr double kSeamDepth = 0.03;       // × the child's radius (add_collar)
constexpr double kMinChildRadius = 0.01;  // metres: thinner children leave no crease to see
constexpr double kCos30 = 0.866;          // sound: a quad within 30° of its corners' normals

// The first τ outside the parent between lo (inside, d_lo deep) and hi (outside, d_hi deep, a
// negative number, or none when no surface lies that way): regula falsi on the depth with the
// Illinois rule (the end kept twice has its depth halved), bisection where a depth is unknown,
// to 4 millionths of the child's radius or a point outside by at most 10⁻⁷ of it.
double crossing(const ParentSurface& parent, const ChildSurface& child, double phi, double lo,
                double d_lo, double hi, std::optional<double> d_hi) {
  const double r = child.radius(lo), tolerance = 4e-6 * r * child.per_metre(lo);
  int kept = 0;  // +1: lo was kept last, −1: hi was
  for (int k = 0; k < 60 && hi - lo > tolerance; ++k) {
    double mid = 0.5 * (lo + hi);
    if (d_hi)
      mid = std::clamp(lo + (hi - lo) * d_lo / (d_lo - *d_hi), lo + 0.01 * (hi - lo),
                       hi - 0.01 * (hi - lo));
    const std::optional<double> d = parent.depth(child.at(mid, phi).position);
    if (d && *d > 0.0) {
      lo = mid, d_lo = *d;
      if (kept == 1 && d_hi) *d_hi *= 0.5;
      kept = 1;
    } else {
      hi = mid, d_hi = d;
      if (d && *d > -1e-7 * r) break;
      if (kept == -1) d_lo *= 0.5;
      kept = -1;
    }
  }
  return hi;
}

// Where the child's surface along azimuth φ leaves the parent's: τ, or none. Stepped along the
// child a quarter of its radius at a time, or further while its point lies deep inside a round
// parent (0.8 of its depth: the ball of that radius is inside, with a margin for the point's
// speed on the outside of a bend) or a displaced one (0.4: the lobes may come nearer sideways).
std::optional<double> exit_of(const ParentSurface& parent, const ChildSurface& child, double phi) {
  double tau = 0.0;
  const std::optional<double> base = parent.depth(child.at(0.0, phi).position);
  if (!base || *base <= 0.0) return 0.0;  // already outside at its base
  double deep = *base;
  const double safe = parent.round() ? 0.8 : 0.4;
  while (true) {
    const double step = std::max(0.25 * child.radius(tau), safe * deep) * child.per_metre(tau);
    const double next = std::min(tau + std::max(step, 1e-4), child.end() - 1e-9);
    if (next <= tau) return std::nullopt;  // never leaves
    const std::optional<double> d = parent.depth(child.at(next, phi).position);
    if (!d || *d <= 0.0) return crossing(parent, child, phi, tau, deep, next, d);
    tau = next, deep = *d;
  }
}

// A fork's two seam rings: on the parent (lower) and the child's disk (upper), sunk into their
// limbs, with each column's directions leaving the parent (toward) and reaching the child
// (along); r is the child's radius at its farthest exit.
struct Rings {
  std::array<SurfaceSample, kSides> lower{}, upper{};
  std::array<glm::dvec3, kSides> toward{}, along{};
  double r = 0.0;
};

// The rings of one fork; none when they do not fit.
std::optional<Rings> rings_of(const ParentSurface& parent, const ChildSurface& child) {
  std::array<double, kSides> exits{};
  std::array<glm::dvec3, kSides> foot{};
  glm::dvec3 centre(0.0);
  double last = 0.0;
  int outside = 0;  // azimuths where the child's base is already outside (a child as thick as
                    // its parent, whose base ring meets the parent's surface)
  for (std::uint32_t k = 0; k < kSides; ++k) {
    const double phi = 2.0 * kPi * k / kSides;
    const std::optional<double> tau = exit_of(parent, child, phi);
    if (!tau) return std::nullopt;
    exits[k] = *tau;
    outside += *tau == 0.0 ? 1 : 0;
    foot[k] = child.at(*tau, phi).position;
    centre += foot[k] / static_cast<double>(kSides);
    last = std::max(last, *tau);
  }
  if (outside == static_cast<int>(kSides)) return std::nullopt;  // not joined to its parent at all
  // The disk (the paper's "far enough along the outgoing limb"), azimuth by azimuth: 0.6 child
  // radii beyond where that side of the child leaves the parent, and on past any point that the
  // tube's own spheres hide (the inside of the child's first bend, where its clamped start turns
  // it away from the parent, Bloomenthal Fig. 5). The ring on the parent: 0.6 child radii (at
  // most half the parent's radius) beyond the footprint, along the parent's surface away from
  // its middle.
  const double r = child.radius(last);
  std::array<double, kSides> disk{};
  for (std::uint32_t k = 0; k < kSides; ++k) {
    const double phi = 2.0 * kPi * k / kSides;
    double d = exits[k] + 0.6 * r * child.per_metre(exits[k]);
    while (d < child.end() && child.hides(d, phi)) d += 0.1 * r * child.per_metre(d);
    if (d >= child.end()) return std::nullopt;
    disk[k] = d;
  }
  Rings rings;
  rings.r = r;
  auto& lower = rings.lower;
  auto& upper = rings.upper;
  for (std::uint32_t k = 0; k < kSides; ++k) {
    const double phi = 2.0 * kPi * k / kSides;
    upper[k] = child.at(disk[k], phi);
    const std::optional<SurfaceSample> at_foot = parent.project(foot[k]);
    if (!at_foot) return std::nullopt;
    glm::dvec3 away = foot[k] - centre;
    away -= at_foot->normal * glm::dot(away, at_foot->normal);
    if (glm::length(away) < 1e-9) return std::nullopt;
    const std::optional<SurfaceSample> q =
        parent.project(foot[k] + glm::normalize(away) * std::min(0.6 * r, 0.5 * at_foot->bark.z));
    if (!q || q->cap) return std::nullopt;
    lower[k] = *q;
    glm::dvec3 back = -(away - q->normal * glm::dot(away, q->normal));
    if (glm::length(back) < 1e-9) return std::nullopt;
    rings.toward[k] = glm::normalize(back);
    rings.along[k] = glm::normalize(child.at(disk[k] + 1e-3, phi).position -
                                    child.at(disk[k] - 1e-3, phi).position);
  }
  // Both seams sink 3 % of the child's radius into their limbs, so the collar's edges are
  // buried and no slit opens where Embree's tube differs a little from the sweep modelled here
  // (at its segments' joints).
  for (std::uint32_t k = 0; k < kSides; ++k) {
    lower[k].position -= lower[k].normal * (kSeamDepth * r);
    upper[k].position -= upper[k].normal * (kSeamDepth * r);
  }
  return rings;
}

// The collar's rows (positions, bark, tangents, the seams' normals) between the rings.
void add_rows(const Rings& rings, RamiformSet& out) {
  double wrap = 0.0;  // the parent's azimuth unwrapped along the ring
  double previous = rings.lower[0].bark.y;
  for (std::uint32_t j = 0; j <= kRows; ++j) {
    const double t = static_cast<double>(j) / kRows;
    const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
    const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
    wrap = 0.0;
    previous = rings.lower[0].bark.y;
    for (std::uint32_t col = 0; col <= kSides; ++col) {
      const std::uint32_t k = col % kSides;
      const SurfaceSample &a = rings.lower[k], &b = rings.upper[k];
      const double span = glm::length(b.position - a.position);
      const glm::dvec3 p = h00 * a.position + h10 * span * rings.toward[k] + h01 * b.position +
                           h11 * span * rings.along[k];
      out.positions.emplace_back(p);
      // Bark: the parent's azimuth unwrapped round the ring, the child's running to 2π.
      double pa = a.bark.y;
      while (pa + wrap - previous > kPi) wrap -= 2.0 * kPi;
      while (pa + wrap - previous < -kPi) wrap += 2.0 * kPi;
      pa += wrap;
      previous = pa;
      const double ca = 2.0 * kPi * col / kSides;
      const glm::dvec3 bark((1 - t) * a.bark.x + t * b.bark.x, (1 - t) * pa + t * ca,
                            (1 - t) * a.bark.z + t * b.bark.z);
      out.bark.emplace_back(bark);
      out.tangents.emplace_back(glm::normalize((1 - t) * a.tangent + t * b.tangent));
      out.normals.emplace_back(j == 0 ? a.normal : j == kRows ? b.normal : glm::dvec3(0.0));
    }
  }
}

// The collar's inside normals and triangles, its vertices from `base`.
void finish_collar(std::uint32_t base, RamiformSet& out) {
  const std::uint32_t w = kSides + 1;
  // Interior normals from the collar's own differences, facing the side the edges' normals face.
  for (std::uint32_t j = 1; j < kRows; ++j) {
    for (std::uint32_t col = 0; col <= kSides; ++col) {
      const std::uint32_t left = col == 0 ? kSides - 1 : col - 1,
                          right = col == kSides ? 1 : col + 1;
      const glm::vec3 around =
          out.positions[base + j * w + right] - out.positions[base + j * w + left];
      const glm::vec3 along =
          out.positions[base + (j + 1) * w + col] - out.positions[base + (j - 1) * w + col];
      glm::vec3 n = glm::cross(around, along);
      const double t = static_cast<double>(j) / kRows;
      const glm::vec3 ref((1 - t) * glm::dvec3(out.normals[base + col]) +
                          t * glm::dvec3(out.normals[base + kRows * w + col]));
      if (glm::dot(n, ref) < 0.0f) n = -n;
      out.normals[base + j * w + col] =
          glm::length(n) > 0.0f ? glm::normalize(n) : glm::normalize(ref);
    }
  }
  for (std::uint32_t j = 0; j < kRows; ++j) {
    for (std::uint32_t col = 0; col < kSides; ++col) {
      const std::uint32_t v0 = base + j * w + col, v1 = v0 + 1, v3 = v0 + w, v2 = v3 + 1;
      out.indices.insert(out.indices.end(), {v0, v1, v3, v2, v3, v1});
    }
  }
}

// The collar of one fork into g.ramiforms; false when it does not fit.
bool add_collar(const ParentSurface& parent, const ChildSurface& child, RamiformSet& out) {
  const std::optional<Rings> rings = rings_of(parent, child);
  if (!rings) return false;
  const auto base = static_cast<std::uint32_t>(out.positions.size());
  add_rows(*rings, out);
  finish_collar(base, out);
  return true;
}

// Whether a collar (vertices from `first`) is sound, as the renderer will see it: its edge rows
// on the parent's and child's surfaces, facing out; its inside outside both limbs (not folded
// into them); no quad turned over (no fold of its own).
bool sound(const RamiformSet& s, std::size_t first, const ParentSurface& parent,
           const ParentSurface& child, double r) {
  const std::uint32_t w = kSides + 1;
  const double e = (kSeamDepth + 0.02) * r;  // the seams' depth and a margin
  for (std::uint32_t j = 0; j <= kRows; ++j) {
    for (std::uint32_t col = 0; col < kSides; ++col) {
      const std::size_t v = first + j * w + col;
      const glm::dvec3 p(s.positions[v]), n(s.normals[v]);
      if (j == 0 || j == kRows) {
        const ParentSurface& limb = j == 0 ? parent : child;
        if (!limb.inside(p - e * n) || limb.inside(p + e * n)) return false;
      } else if (parent.inside(p + 2.0 * e * n) || child.inside(p + 2.0 * e * n)) {
        return false;
      }
      if (j == kRows) continue;
      const glm::dvec3 around(s.positions[v + 1] - s.positions[v]);
      const glm::dvec3 along(s.positions[v + w] - s.positions[v]);
      const glm::dvec3 face = glm::cross(around, along);
      // A quad must have area, and face the way its corners' normals do (within 30°: the
      // normals shade it, and a shading normal further off the face shows as a crease).
      const double area = glm::length(face);
      if (area < 1e-6 * r * r) return false;
      bool agrees = true;
      for (const std::size_t corner : {v, v + 1, v + w, v + w + 1})
        agrees = agrees && glm::dot(face / area, glm::dvec3(s.normals[corner])) > kCos30;
      if (!agrees) return false;
    }
  }
  return true;
}

bool finite(const RamiformSet& s, std::size_t from) {
  for (std::size_t i = from; i < s.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(s.positions[i][c]) || !std::isfinite(s.normals[i][c]) ||
          !std::isfinite(s.bark[i][c]))
        return false;
    }
  }
  return true;
}

}  // namespace

void add_ramiforms(const std::vector<Limb>& limbs, TreeGeometry& g) {
  RamiformSet& out = g.ramiforms;
  for (std::size_t c = 0; c < limbs.size(); ++c) {
    const Limb& child = limbs[c];
    if (child.parent < 0 || limbs[static_cast<std::size_t>(child.parent)].level > 1) continue;
    const ChildSurface child_surface(g.curves, static_cast<std::int32_t>(c));
    const ParentSurface parent(g, child.parent);
    if (child_surface.end() == 0.0 || !parent.valid()) {
      ++g.stats.ramiform_forks;
      ++g.stats.ramiforms_skipped;  // a displaced child (a clone of a flared trunk)
      continue;
    }
    // Forks large enough to see: a child of at least 1 cm and a quarter of its parent's radius.
    if (child_surface.end() > 0.0 && child_surface.radius(0.0) < kMinChildRadius) continue;
    const std::optional<SurfaceSample> base =
        child_surface.end() > 0.0 ? parent.project(child_surface.at(0.0, 0.0).position)
                                  : std::nullopt;
    if (base && child_surface.radius(0.0) < 0.25 * base->bark.z) continue;
    const bool trunk = limbs[static_cast<std::size_t>(child.parent)].level == 0;
    ++g.stats.ramiform_forks;
    g.stats.ramiform_trunk_forks += trunk ? 1 : 0;
    const std::size_t vertices = out.positions.size(), indices = out.indices.size();
    const ParentSurface child_limb(g, static_cast<std::int32_t>(c));
    if (!add_collar(parent, child_surface, out) || !finite(out, vertices) ||
        !sound(out, vertices, parent, child_limb, child_surface.radius(0.0))) {
      out.positions.resize(vertices);
      out.normals.resize(vertices);
      out.tangents.resize(vertices);
      out.bark.resize(vertices);
      out.indices.resize(indices);
      ++g.stats.ramiforms_skipped;
      continue;
    }
    g.stats.ramiform_trunk_collars += trunk ? 1 : 0;
    RamiformFork fork;
    fork.parent_limb = child.parent;
    fork.child_limb = static_cast<std::int32_t>(c);
    fork.first_vertex = static_cast<std::uint32_t>(vertices);
    const CurveSegment& first = g.curves.segments[child_surface.first()];
    fork.lod_level = first.lod_level;
    fork.lod_item = first.lod_item;
    out.forks.push_back(fork);
  }
  g.stats.ramiforms = out.forks.size();
  g.stats.ramiform_triangles = out.triangle_count();
}

}  // namespace arbor::generator
