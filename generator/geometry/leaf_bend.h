// A shaped leaf (issue 45; docs/geometry.md, "Shaped leaves"): the flat unit leaf of a LeafShape
// (x across in [-0.5, 0.5] × its width, y along in [0, 1] × its length) bent without stretching —
// folded along the midrib, cupped across, curled along and twisted about the midrib — and drawn
// as a grid of hinged panels (Bloomenthal's hinged leaf, §10, generalised) whose corners lie on
// the bent surface and carry its normals, so that shading is smooth across the panels.
//
// The bend, in the leaf's frame (A across = axis × normal, T along = axis, U up = normal):
//   cross-section  at lateral distance d = |x| w from the midrib the blade rises at the angle
//                  θ(d) = fold + cup · d / (w/2) (radians; each half mirrored), so a point lies
//                  a(d) = ∫cos θ across and h(d) = ∫sin θ up: arc length across is kept;
//   curl           the midrib bends with constant curvature through `curl` from base to tip
//                  (positive: the tip droops towards the leaf's back), its arc length kept: at
//                  y the midrib's tangent is T cos φ − U sin φ with φ = curl · y;
//   twist          the cross-section turns about the midrib's tangent by twist · y.
// A leaf with every angle 0 is flat, one card as before (images unchanged).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace arbor::generator {

struct LeafBend {
  float fold = 0.0f, cup = 0.0f, curl = 0.0f, twist = 0.0f;  // radians

  // From a look's degrees.
  static LeafBend from_degrees(double fold, double cup, double curl, double twist);
  bool flat() const { return fold == 0.0f && cup == 0.0f && curl == 0.0f && twist == 0.0f; }
  // Panels: across each half of the blade (1 for a fold alone, more as the cup turns it) and
  // along (as curl and twist turn it): at most 20° of turn per panel (the smooth normals
  // carry the curvature between the corners).
  int columns_per_half() const;
  int rows() const;

  // A leaf point (x, y) of a leaf of width w and length l, as (across, along, up) in the leaf's
  // frame, metres from the leaf's base; and the bent surface's unit normal there, on the up side
  // (at the midrib, x = 0, the mean of the two halves': the fold's crease is shaded smooth).
  glm::vec3 place(float x, float y, float w, float l) const;
  glm::vec3 normal(float x, float y, float w, float l) const;
};

}  // namespace arbor::generator
