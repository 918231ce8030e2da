// Ünal's fractal tree model (MS thesis 1995, §3): the basic recursive model (children on a cone
// whose tip is the parent's tip), the refined model (stochastic pruning, perturbed axes and radii)
// and the time-aware model (depth and size from age). Grows a Skeleton.
#pragma once

#include <cstdint>

#include "generator/grow_options.h"
#include "generator/skeleton.h"

namespace arbor::generator {

struct FractalParams {
  // Basic model (thesis Table 3.1).
  int depth = 5;             // levels of branches at full age (the trunk is level 0)
  int branches = 3;          // children per branch (fan-out) before pruning
  double cone_angle = 60.0;  // degrees: top (apex) angle of the cone the children lie on
  double size_ratio = 0.7;   // child length / parent length
  double taper = 0.65;       // radius at a branch's top / at its bottom
  double length = 3.0;       // metres, the trunk at full size
  double radius = 0.15;      // metres, the trunk's base at full size
  int discs = 6;             // points along each branch's axis (≥ 2)
  double twist = 137.5;      // degrees the children's cone turns per level (arbor's addition)
  // Refined model (§3.2).
  double prune = 0.0;             // probability that a proposed child is pruned
  double length_variation = 0.0;  // relative ± of each branch's length
  double angle_variation = 0.0;   // relative ± of each child's angles
  double wiggle = 0.0;            // disc centres moved ⟂ the axis by ± this × branch length
  double radius_variation = 0.0;  // relative ± of each disc's radius
  // Time-aware model (§3.3).
  double years_per_level = 4.0;  // n: a level is born every n units of time
  double age = 0.0;              // 0: full grown (used when no --time is given)
  double cone_widening = 0.5;    // young children start in a cone this much narrower
  // Leaves at the tips of the outermost branches.
  int leaves = 0;
  double leaf_length = 0.1, leaf_width = 0.06;
  int leaf_shape = 0;
};

// §3.3 growth factor of a branch of age a when a level is born every n: a / n up to n/2, then
// 1 − n / (4a) (0.5 at n/2, 0.75 at n, 0.875 at 2n, 0.9375 at 4n); 0 before birth.
double fractal_growth(double age, double years_per_level);

// The age at which the tree is full grown: its last level is 4n old.
double fractal_full_age(const FractalParams& p);

// Branches the tree can have (before pruning), for the size limit.
double fractal_estimate(const FractalParams& p);

// The fractal model reads seed, time (its age: 0 means p.age, and p.age 0 means full grown),
// max_stems and force.
using FractalOptions = GrowOptions;

Skeleton grow_fractal(const FractalParams& params, const FractalOptions& options);

}  // namespace arbor::generator
