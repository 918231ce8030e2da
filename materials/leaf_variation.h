// Leaf-to-leaf colour variation (issue 29): every leaf of a crown gets its own deterministic tint
// of the species' leaf, drawn from a documented distribution keyed by the leaf, so that a crown is
// not one uniform green. Three parameters, all 0 (no variation) by default:
//   value  σ_v: the spread of ln brightness (every channel alike) — leaves differ in thickness,
//          water and pigment content;
//   hue    σ_h: the spread along arbor's chlorophyll axis: a leaf with less chlorophyll is
//          lighter in red, a little lighter in green and unchanged in blue (chlorophyll absorbs
//          mostly red and blue, carotenoids keep absorbing blue), so ln tint gains s · (1, 0.35, 0)
//          for s ~ N(0, σ_h) — yellower for s > 0, deeper green for s < 0;
//   crown  g: ln brightness from the crown's bottom (h = 0) to its top (h = 1), added as
//          g (h − ½): sun leaves at the top are lighter than shade leaves below.
// With z₁, z₂ standard normal variates of the leaf (clamped to ±3):
//   ln tint_c = σ_v z₁ − σ_v²/2 + d_c (σ_h z₂ − σ_h² d_c / 2) + g (h − ½),   d = (1, 0.35, 0),
// so the tint's mean is exactly 1 in every channel at mid-crown (before the clamp, which moves it
// by less than 0.3 %): variation does not change a crown's mean colour. Reflectance and
// transmittance are multiplied alike, and LeafMaterial keeps their sum at most 1 per channel.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace arbor::materials {

struct LeafVariation {
  float value = 0.0f;  // σ_v
  float hue = 0.0f;    // σ_h
  float crown = 0.0f;  // g

  bool any() const { return value != 0.0f || hue != 0.0f || crown != 0.0f; }
  // The tint of the leaf with this key at normalised height h in its crown.
  glm::vec3 tint(std::uint64_t key, float crown_height) const;
};

// The season's tint of a leaf (docs/species-format.md, "Seasons"): in spring every leaf is
// multiplied by `spring`; in autumn a leaf turns with probability `turned`, by its key, and then
// has autumn^m with m uniform in [kLeastTurn, 1] — part-way (the geometric mean: pigments absorb)
// or fully to the species' autumn colour (autumn = that colour ÷ the summer front reflectance,
// per channel).
struct LeafSeason {
  // The least a turned leaf turns: at its peak a tree in autumn colour is mostly turned leaves
  // (0.5 made a scarlet tupelo rust-brown: docs/species-format.md, "Seasons").
  static constexpr double kLeastTurn = 0.75;
  glm::vec3 spring{1.0f};
  glm::vec3 autumn{1.0f};
  float turned = 0.0f;

  bool any() const { return turned > 0.0f || spring != glm::vec3(1.0f); }
  glm::vec3 tint(std::uint64_t key) const;
};

}  // namespace arbor::materials
