// A leaf's margin: the outline of a LeafShape (leaf_shapes.h) cut into teeth along its edge.
//
// The teeth are radial cuts into each star-shaped part of the outline (so a part stays
// star-shaped about its centre and its fan still triangulates it), spaced evenly by arc length
// in the leaf's own proportions (x × the blade's width, y × its length, so that a narrow leaf's
// teeth are as long as they are deep on its sides), fading out at the blade's base and tip and
// absent where an edge lies inside another part (a leaflet's base under its neighbour).
#pragma once

#include <array>
#include <cstddef>

namespace arbor::generator {

struct LeafShape;
struct LeafOutline;

// Smooth as the outline is; toothed with teeth pointing towards the tip (saw-edged, as an elm's or
// a birch's); scalloped with round teeth and sharp notches (an aspen's); waved into shallow round
// lobes with round sinuses (a chestnut oak's).
enum class LeafMargin { Entire, Serrate, Crenate, Lobed };
inline constexpr std::array<const char*, 4> kLeafMarginNames = {"entire", "serrate", "crenate",
                                                                "lobed"};

struct LeafMarginSpec {
  LeafMargin kind = LeafMargin::Entire;
  int teeth = 20;       // along each side of the blade
  double depth = 0.03;  // of a notch below the outline, × the blade's width
  bool entire() const { return kind == LeafMargin::Entire || depth <= 0.0; }
};

// How far a point of the margin lies below the outline, as a fraction of the depth, at `phase`
// in [0, 1) through its tooth (0 and 1: the notches' ends), travelling towards the tip.
double margin_profile(LeafMargin kind, double phase);

// The outline `base` (its star-shaped parts) with the margin's teeth, for leaves whose width is
// `aspect` × their length.
LeafShape margined_shape(const LeafOutline& base, const LeafMarginSpec& margin, double aspect);

// The index (leaf_shape(), leaf_outline()) of `base`'s outline with the margin, made once per
// distinct (base, margin, aspect) and kept for the program's life; `base` itself when the margin
// is entire. The aspect is rounded to 1/32 of an octave, so leaves of one species share one.
std::size_t margined_shape_index(std::size_t base, const LeafMarginSpec& margin, double aspect);

}  // namespace arbor::generator
