// The shaped leaf's bend (leaf_bend.h), in double precision.
#include "generator/geometry/leaf_bend.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "common/math.h"

namespace arbor::generator {

namespace {

constexpr double kPanelTurn = 20.0 * kPi / 180.0;  // radians of turn a panel may span

int panels_for(double turn) {
  return std::clamp(static_cast<int>(std::ceil(std::fabs(turn) / kPanelTurn - 1e-9)), 1, 12);
}

// ∫₀^s (cos(a + k t), sin(a + k t)) dt: a planar arc of constant curvature k, leaving at angle a.
glm::dvec2 arc(double a, double k, double s) {
  if (std::fabs(k * s) < 1e-9) return {s * std::cos(a), s * std::sin(a)};
  return {(std::sin(a + k * s) - std::sin(a)) / k, (std::cos(a) - std::cos(a + k * s)) / k};
}

// The bent point in the leaf frame (across, along, up), doubles.
glm::dvec3 bent(const LeafBend& b, double x, double y, double w, double l) {
  const double half = 0.5 * w;
  const double side = x < 0.0 ? -1.0 : 1.0;
  const glm::dvec2 cross = arc(b.fold, b.cup / half, std::fabs(x) * w);
  // The midrib: an arc in the (along, up) plane curling towards −up by `curl` over its length.
  const glm::dvec2 rib = arc(0.0, -b.curl / l, y * l);  // (along, up)
  const double phi = -b.curl * y;                       // the midrib tangent's angle up
  const glm::dvec3 up0(0.0, -std::sin(phi), std::cos(phi));
  const glm::dvec3 across0(1.0, 0.0, 0.0);
  const double tau = b.twist * y;
  const glm::dvec3 across = across0 * std::cos(tau) + up0 * std::sin(tau);
  const glm::dvec3 up = up0 * std::cos(tau) - across0 * std::sin(tau);
  return glm::dvec3(0.0, rib.x, rib.y) + across * (side * cross.x) + up * cross.y;
}

}  // namespace

LeafBend LeafBend::from_degrees(double fold, double cup, double curl, double twist) {
  const double r = kPi / 180.0;
  LeafBend b;
  b.fold = static_cast<float>(fold * r);
  b.cup = static_cast<float>(cup * r);
  b.curl = static_cast<float>(curl * r);
  b.twist = static_cast<float>(twist * r);
  return b;
}

int LeafBend::columns_per_half() const { return panels_for(cup); }

int LeafBend::rows() const { return std::max(panels_for(curl), panels_for(twist)); }

glm::vec3 LeafBend::place(float x, float y, float w, float l) const {
  return glm::vec3(bent(*this, x, y, w, l));
}

glm::vec3 LeafBend::normal(float x, float y, float w, float l) const {
  // The surface's tangents by central differences of the exact bend, each half on its own side
  // of the midrib (the crease would blur them), their cross product facing up: (across × along).
  const double e = 1e-4;
  const double yc = std::clamp(static_cast<double>(y), e, 1.0 - e);
  auto half_normal = [&](double sx) {
    const double x0 = sx * std::max(std::fabs(static_cast<double>(x)), e);
    const glm::dvec3 du = bent(*this, x0 + sx * e, yc, w, l) - bent(*this, x0 - sx * e, yc, w, l);
    const glm::dvec3 dv = bent(*this, x0, yc + e, w, l) - bent(*this, x0, yc - e, w, l);
    return glm::normalize(glm::cross(sx * du, dv));
  };
  const glm::dvec3 n = x == 0.0f ? glm::normalize(half_normal(1.0) + half_normal(-1.0))
                                 : half_normal(x < 0.0f ? -1.0 : 1.0);
  return glm::vec3(n);
}

}  // namespace arbor::generator
