// The five weights of TREE-MAKER's shade (Neighbors & Hodges 1990, §III, Figure 3): ambient,
// N·L, height h/h0, radius r/r0 and the angle term sin(q/2), with arbor's defaults
// (docs/treemaker-format.md). A template's `light {}` section or a scene may set others.
#pragma once

namespace arbor::materials {

struct TreemakerWeights {
  double ambient = 0.1, lambert = 0.4, height = 0.2, radius = 0.2, angle = 0.1;
};

}  // namespace arbor::materials
