// Weber & Penn 1995 §4.5 and §4.9: a leaf's orientation from its placement turns, and its turn
// toward the light, for every leaf of a tree at once.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "generator/skeleton.h"

namespace arbor::generator::wp {

// A placed leaf before orientation: the frame of the stem segment it grows from, the azimuth
// `turn` about the segment's z axis and the down angle `down` about the turned x axis (radians,
// within [−π, π]).
struct PendingLeaf {
  glm::vec3 x, y, z;
  float turn, down;
};

// §4.9, read geometrically: first turn the leaf about the vertical through its position by
// bend·θ_bend (so its normal's azimuth moves toward the leaf's own azimuth: facing outward),
// then tilt it about the horizontal axis across its normal by bend·φ_bend (toward facing up).
// θ_bend, the position's azimuth less the normal's, is taken as one signed angle in (−π, π].
void orient_toward_light(float bend, float at_x, float at_y, glm::vec3& axis, glm::vec3& normal);

// Sets leaves[i]'s axis and normal from pending[i] (§4.5) and turns it toward the light by
// `bend` (LeafBend, §4.9). Single precision, the precision leaves are stored in, with
// common/fast_trig.h, in one loop of independent leaves: leaf by leaf in double precision with
// glibc's sines and arc tangents, a dependent chain per leaf, this was 60 % of growing the weeping
// willow (perf, issue 31).
void orient_leaves(const std::vector<PendingLeaf>& pending, float bend, std::vector<Leaf>& leaves);

}  // namespace arbor::generator::wp
