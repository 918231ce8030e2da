// Bloomenthal §2–5: a limb as a C2 interpolating cubic spline through its skeleton points, with
// chord-length parameters and clamped end tangents, plus rotation-minimising frames along it.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace arbor::generator {

using DVec3 = glm::dvec3;

// A C2 cubic spline in Hermite form: knots p_i at parameters t_i (cumulative chord length, so
// the parameter is close to arc length in metres) with derivatives d_i = dP/dt there.
struct CubicSpline {
  std::vector<DVec3> points;
  std::vector<double> params;
  std::vector<DVec3> derivatives;

  std::size_t segment_count() const { return points.empty() ? 0 : points.size() - 1; }
  // The segment containing t (clamped to the ends) and the local u in [0, 1].
  std::size_t locate(double t, double& u) const;
  // locate's answer, found without a search when t lies in segment `hint` (as the samples of one
  // piece do): the same segment and u, bit for bit.
  std::size_t locate_from(std::size_t hint, double t, double& u) const;
  DVec3 position(double t) const;
  DVec3 derivative(double t) const;         // dP/dt
  DVec3 second_derivative(double t) const;  // d²P/dt²
  // Curvature |P' × P''| / |P'|³ at t (0 where the speed vanishes).
  double curvature(double t) const;
  double curvature_in(std::size_t segment, double u) const;  // at u of a segment locate gave
  // Values on one side of knot i (side -1: end of segment i-1, +1: start of segment i), for
  // continuity checks at interior knots.
  DVec3 second_derivative_at_knot(std::size_t i, int side) const;
};

// Fits the C2 spline through `points` (at least 2) with the end derivatives clamped to
// `start_derivative` and `end_derivative` (dP/dt, so a unit vector is unit speed). Coincident
// consecutive points are given a tiny parameter step so the system stays solvable.
CubicSpline fit_c2_spline(const std::vector<DVec3>& points, const DVec3& start_derivative,
                          const DVec3& end_derivative);

// A rotation-minimising frame: `normal` ⟂ `tangent`, both unit; binormal = tangent × normal.
struct FrameSample {
  DVec3 tangent;
  DVec3 normal;
};

// Rotation-minimising frames at parameters `ts` (increasing), starting from `initial_normal`
// (projected to be ⟂ the first tangent), by the double-reflection method of Wang et al. 2008.
// Frenet frames fail on straight parts and flip at inflections; these do neither.
std::vector<FrameSample> rotation_minimizing_frames(const CubicSpline& spline,
                                                    const std::vector<double>& ts,
                                                    const DVec3& initial_normal);

// A unit vector ⟂ v (deterministic).
DVec3 any_perpendicular(const DVec3& v);

}  // namespace arbor::generator
