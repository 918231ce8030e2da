// C2 cubic spline fitting (tridiagonal system in the knot derivatives) and RMF frames.
#include "generator/geometry/limb_splines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"

namespace arbor::generator {

namespace {

// Hermite basis on u in [0, 1] for a segment of parameter length h.
struct Hermite {
  DVec3 p0, p1, m0, m1;  // m = derivative × h (derivative with respect to u)
  DVec3 at(double u) const {
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 +
           (u3 - u2) * m1;
  }
  DVec3 d1(double u) const {  // d/du
    const double u2 = u * u;
    return (6 * u2 - 6 * u) * p0 + (3 * u2 - 4 * u + 1) * m0 + (-6 * u2 + 6 * u) * p1 +
           (3 * u2 - 2 * u) * m1;
  }
  DVec3 d2(double u) const {  // d²/du²
    return (12 * u - 6) * p0 + (6 * u - 4) * m0 + (-12 * u + 6) * p1 + (6 * u - 2) * m1;
  }
};

Hermite segment_of(const CubicSpline& s, std::size_t i) {
  const double h = s.params[i + 1] - s.params[i];
  return {s.points[i], s.points[i + 1], s.derivatives[i] * h, s.derivatives[i + 1] * h};
}

}  // namespace

DVec3 any_perpendicular(const DVec3& v) {
  const DVec3 a = std::fabs(v.z) < 0.9 ? DVec3(0, 0, 1) : DVec3(1, 0, 0);
  return glm::normalize(glm::cross(a, v));
}

std::size_t CubicSpline::locate(double t, double& u) const {
  ARBOR_CHECK(points.size() >= 2);
  const auto it = std::upper_bound(params.begin(), params.end(), t);
  std::size_t i = it == params.begin() ? 0 : static_cast<std::size_t>(it - params.begin()) - 1;
  i = std::min(i, segment_count() - 1);
  const double h = params[i + 1] - params[i];
  u = std::clamp((t - params[i]) / h, 0.0, 1.0);
  return i;
}

DVec3 CubicSpline::position(double t) const {
  double u = 0.0;
  const std::size_t i = locate(t, u);
  return segment_of(*this, i).at(u);
}

DVec3 CubicSpline::derivative(double t) const {
  double u = 0.0;
  const std::size_t i = locate(t, u);
  return segment_of(*this, i).d1(u) / (params[i + 1] - params[i]);
}

DVec3 CubicSpline::second_derivative(double t) const {
  double u = 0.0;
  const std::size_t i = locate(t, u);
  const double h = params[i + 1] - params[i];
  return segment_of(*this, i).d2(u) / (h * h);
}

DVec3 CubicSpline::second_derivative_at_knot(std::size_t i, int side) const {
  if (side < 0) {
    const double h = params[i] - params[i - 1];
    return segment_of(*this, i - 1).d2(1.0) / (h * h);
  }
  const double h = params[i + 1] - params[i];
  return segment_of(*this, i).d2(0.0) / (h * h);
}

std::size_t CubicSpline::locate_from(std::size_t hint, double t, double& u) const {
  const std::size_t n = segment_count();
  // The conditions under which locate's search ends at `hint` (its clamping included).
  if (hint >= n || (hint > 0 && !(params[hint] <= t)) || (hint + 1 < n && !(t < params[hint + 1])))
    return locate(t, u);
  u = std::clamp((t - params[hint]) / (params[hint + 1] - params[hint]), 0.0, 1.0);
  return hint;
}

double CubicSpline::curvature(double t) const {
  // derivative(t) and second_derivative(t), sharing one search and one segment.
  double u = 0.0;
  const std::size_t i = locate(t, u);  // before u is read: argument order is unspecified
  return curvature_in(i, u);
}

double CubicSpline::curvature_in(std::size_t i, double u) const {
  const Hermite segment = segment_of(*this, i);
  const double h = params[i + 1] - params[i];
  const DVec3 d1 = segment.d1(u) / h, d2 = segment.d2(u) / (h * h);
  const double speed = glm::length(d1);
  if (speed < 1e-12) return 0.0;
  return glm::length(glm::cross(d1, d2)) / (speed * speed * speed);
}

CubicSpline fit_c2_spline(const std::vector<DVec3>& points, const DVec3& start_derivative,
                          const DVec3& end_derivative) {
  ARBOR_CHECK(points.size() >= 2);
  const std::size_t n = points.size() - 1;  // segments
  CubicSpline s;
  s.points = points;
  s.params.resize(n + 1);
  s.params[0] = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    // Chord-length ("distance-adjusted") parameters, Rogers & Adams via Bloomenthal §2.
    s.params[i + 1] = s.params[i] + std::max(glm::length(points[i + 1] - points[i]), 1e-9);
  }
  s.derivatives.assign(n + 1, DVec3(0.0));
  s.derivatives[0] = start_derivative;
  s.derivatives[n] = end_derivative;
  if (n == 1) return s;

  // Interior knots i = 1..n-1: C2 continuity gives
  //   h_i m_{i-1} + 2 (h_{i-1} + h_i) m_i + h_{i-1} m_{i+1}
  //     = 3 [h_i (p_i - p_{i-1}) / h_{i-1} + h_{i-1} (p_{i+1} - p_i) / h_i].
  // Solved with the Thomas algorithm (the matrix is diagonally dominant).
  const std::size_t m = n - 1;
  std::vector<double> lower(m), diag(m), upper(m);
  std::vector<DVec3> rhs(m);
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = k + 1;
    const double h0 = s.params[i] - s.params[i - 1], h1 = s.params[i + 1] - s.params[i];
    lower[k] = h1;
    diag[k] = 2.0 * (h0 + h1);
    upper[k] = h0;
    rhs[k] = 3.0 * (h1 * (points[i] - points[i - 1]) / h0 + h0 * (points[i + 1] - points[i]) / h1);
  }
  rhs[0] -= lower[0] * s.derivatives[0];
  rhs[m - 1] -= upper[m - 1] * s.derivatives[n];
  for (std::size_t k = 1; k < m; ++k) {
    const double w = lower[k] / diag[k - 1];
    diag[k] -= w * upper[k - 1];
    rhs[k] -= w * rhs[k - 1];
  }
  s.derivatives[m] = rhs[m - 1] / diag[m - 1];
  for (std::size_t k = m - 1; k-- > 0;) {
    s.derivatives[k + 1] = (rhs[k] - upper[k] * s.derivatives[k + 2]) / diag[k];
  }
  return s;
}

std::vector<FrameSample> rotation_minimizing_frames(const CubicSpline& spline,
                                                    const std::vector<double>& ts,
                                                    const DVec3& initial_normal) {
  std::vector<FrameSample> frames;
  frames.reserve(ts.size());
  auto unit_tangent = [&](double t) {
    DVec3 d = spline.derivative(t);
    if (glm::length(d) < 1e-12) {
      // Zero speed (a clamped tangent of zero): use the direction the curve leaves in.
      d = spline.second_derivative(t);
      if (glm::length(d) < 1e-12) d = spline.position(t + 1e-6) - spline.position(t);
    }
    return glm::normalize(d);
  };
  DVec3 t0 = unit_tangent(ts.front());
  DVec3 r0 = initial_normal - t0 * glm::dot(initial_normal, t0);
  r0 = glm::length(r0) > 1e-9 ? glm::normalize(r0) : any_perpendicular(t0);
  frames.push_back({t0, r0});
  for (std::size_t i = 1; i < ts.size(); ++i) {
    const DVec3 x0 = spline.position(ts[i - 1]), x1 = spline.position(ts[i]);
    const DVec3 t1 = unit_tangent(ts[i]);
    // Double reflection: reflect across the bisector plane of x0→x1, then across the plane
    // between the reflected tangent and the new tangent.
    const DVec3 v1 = x1 - x0;
    const double c1 = glm::dot(v1, v1);
    DVec3 r_left = r0, t_left = t0;
    if (c1 > 1e-24) {
      r_left = r0 - (2.0 / c1) * glm::dot(v1, r0) * v1;
      t_left = t0 - (2.0 / c1) * glm::dot(v1, t0) * v1;
    }
    const DVec3 v2 = t1 - t_left;
    const double c2 = glm::dot(v2, v2);
    DVec3 r1 = c2 > 1e-24 ? r_left - (2.0 / c2) * glm::dot(v2, r_left) * v2 : r_left;
    r1 = r1 - t1 * glm::dot(r1, t1);
    r1 = glm::length(r1) > 1e-12 ? glm::normalize(r1) : any_perpendicular(t1);
    frames.push_back({t1, r1});
    t0 = t1;
    r0 = r1;
  }
  return frames;
}

}  // namespace arbor::generator
