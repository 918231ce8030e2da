// A procedural leaf texture over the leaf's uv (issue 29), so that close-ups are not flat colour:
// the midrib, pinnate secondary veins and the margin, each paler and yellower than the blade (the
// veins' tissue holds less chlorophyll). u runs across the leaf (0.5 the midrib), v along it
// (0 base, 1 tip). Arbor's pattern, not a measurement:
//   midrib     half-width 0.025 (1 − 0.7 v) of the leaf's width, tapering to the tip;
//   veins      `pairs` pairs leaving the midrib toward the tip, along v − 1.2 |u − ½| = const,
//              half-width 0.012 of the leaf's length, fading out before the margin;
//   margin     the outer eighth of the card's width on each side (a leaf's outline is narrower
//              than its card near base and tip, so there the margin falls outside the blade).
// The mask m ∈ [0, 1] is the largest of the three (secondary veins at 0.7, the margin at 0.5),
// with smooth edges; the tint is exp(s m (0.45, 0.30, 0.15)) for strength s: 1 on the blade
// between the veins, paler and yellower on them. LeafMaterial keeps R + T ≤ 1 after tinting.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace arbor::materials {

struct LeafTexture {
  float strength = 0.0f;  // s; 0: no texture
  int pairs = 8;          // secondary vein pairs

  bool any() const { return strength != 0.0f; }
  // The vein-and-margin mask at leaf uv, in [0, 1].
  float mask(glm::vec2 uv) const;
  glm::vec3 tint(glm::vec2 uv) const;
};

}  // namespace arbor::materials
