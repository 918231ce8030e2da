// limbs::fit (Bloomenthal §5): turns a Skeleton's stems into limbs, each one C2 spline through a
// chain of skeleton points. At a branch point the dominant outgoing stem continues the incoming
// spline; every other outgoing stem starts a spline of its own whose initial tangent is clamped
// to the parent's direction, scaled by a tension.
#pragma once

#include <cstdint>
#include <vector>

#include "generator/geometry/limb_splines.h"
#include "generator/skeleton.h"

namespace arbor::generator {

// A knot of a limb: which skeleton point it is.
struct KnotRef {
  std::int32_t stem = 0;
  std::uint32_t point = 0;  // index within the stem's points
};

struct Limb {
  std::vector<KnotRef> knots;
  CubicSpline spline;
  std::vector<DVec3> knot_normals;  // rotation-minimising frame normal at each knot
  std::vector<double> knot_arc;     // bark arc length (metres) at each knot
  std::int32_t parent = -1;         // the limb it branches from; -1 for the root
  double parent_param = 0.0;        // spline parameter on the parent where it branches
  double tension = 1.0;             // scale of the clamped initial tangent (1 large … 0 twig)
  bool tension_raised = false;      // raised above branch_tension() for Embree's radius rule
  std::int32_t level = 0;           // level of its first stem

  // The stem a segment belongs to (that of its end knot) and the stem's normalised position z.
  std::int32_t segment_stem(std::size_t segment) const { return knots[segment + 1].stem; }
  double z_at(const Skeleton& sk, double t) const;
  // Limb radius at parameter t, from the stems' taper laws (or their point radii).
  double radius_at(const Skeleton& sk, double t) const;
  // z_at and radius_at at u of a segment that spline.locate gave.
  double z_in(const Skeleton& sk, std::size_t segment, double u) const;
  double radius_in(const Skeleton& sk, std::size_t segment, double u) const;
  // Bark arc length at parameter t (interpolated between knots).
  double arc_at(double t) const;
  // Frame normal at t, transported from the previous knot (rotation-minimising).
  DVec3 normal_at(double t) const;
};

// The tension of a non-dominant limb from its radius relative to its parent's there: the ratio
// itself, so equal radii give 1 and twigs approach the floor (tension 0 would stop the curve
// dead at its base, a zero-speed point where curvature is undefined).
double branch_tension(double child_radius, double parent_radius);
constexpr double kMinTension = 0.1;

// Radii within this fraction of each other count as "nearly equal" (dominance by direction).
constexpr double kNearlyEqualRadius = 0.05;

// Largest radius × curvature over the limb's first spline segment (Embree needs it below 1).
double start_bend_ratio(const Skeleton& skeleton, const Limb& limb);

// A child limb starts on its parent's spline (what the renderer draws), not at its skeleton point
// on the chord between the parent's points, which may lie centimetres off the drawn axis
// (docs/geometry.md, "Limbs").
std::vector<Limb> fit_limbs(const Skeleton& skeleton);

}  // namespace arbor::generator
