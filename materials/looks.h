// The parameters of arbor's materials as species files and scenes state them: bark, leaves and
// TREE-MAKER's shading weights. Plain data, read by formats/, turned into materials by scene/.
#pragma once

#include "common/math.h"

namespace arbor::mat {

// Default bark of a species (scene files may override it).
struct BarkLook {
  arbor::Rgb albedo{0.30, 0.26, 0.22};
  double bump_height = 0.004;  // metres of relief
  double roughness = 0.0;      // degrees: Oren–Nayar slope deviation σ (0: Lambertian)
};

// Default leaves of a species: front reflectance, the lighter back, diffuse transmittance.
struct LeafLook {
  arbor::Rgb reflectance{0.06, 0.20, 0.04};
  arbor::Rgb back_reflectance{0.10, 0.24, 0.07};
  arbor::Rgb transmittance{0.05, 0.18, 0.03};
  double hinge_angle = 0.0;  // degrees; > 0: Bloomenthal's hinged three-polygon leaf (§10)
};

// The five weights of TREE-MAKER's shade (Neighbors & Hodges 1990, §III, Figure 3): ambient,
// N·L, height h/h0, radius r/r0 and the angle term sin(q/2). These defaults are arbor's
// (docs/treemaker-format.md); a template's `light {}` section or a scene may set others.
struct TreemakerWeights {
  double ambient = 0.1, lambert = 0.4, height = 0.2, radius = 0.2, angle = 0.1;
};

}  // namespace arbor::mat
