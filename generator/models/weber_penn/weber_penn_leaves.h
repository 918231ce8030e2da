// Weber & Penn 1995 §4.5 and §4.9: a leaf's orientation from its placement turns, and its turn
// toward the light, for every leaf of a tree at once.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "generator/skeleton.h"

namespace arbor::generator::wp {

// §4.9, read geometrically: first turn the leaf about the vertical through its position by
// bend·θ_bend (so its normal's azimuth moves toward the leaf's own azimuth: facing outward),
// then tilt it about the horizontal axis across its normal by bend·φ_bend (toward facing up).
// θ_bend, the position's azimuth less the normal's, is taken as one signed angle in (−π, π].
// One leaf at a time: the readable statement that LeafOrienter's vectorised block is tested
// against bit for bit (growth uses LeafOrienter).
void orient_toward_light(float bend, float at_x, float at_y, glm::vec3& axis, glm::vec3& normal);

// Orients leaves as they are placed, a block at a time: each leaf's axis and normal from its
// segment's frame and turns (§4.5), turned toward the light by `bend` (LeafBend, §4.9), exactly as
// orient_toward_light does it. Single precision, the precision leaves are stored in, with
// common/fast_trig.h, in a loop over a block of independent leaves that the compiler vectorises:
// leaf by leaf in double precision with glibc's sines and arc tangents, a dependent chain per leaf,
// this was 60 % of growing the weeping willow (perf, issue 31).
class LeafOrienter {
 public:
  static constexpr std::size_t kBlock = 256;

  LeafOrienter(float bend, std::vector<Leaf>& leaves) : bend_(bend), leaves_(leaves) {}
  // The leaf last appended to `leaves` (its position set) grows from a segment with frame
  // (x, y, z), turned by `turn` about z and then by `down` about the turned x (radians, [−π, π]).
  void add(const glm::vec3& x, const glm::vec3& y, const glm::vec3& z, float turn, float down) {
    const float values[11] = {x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z, turn, down};
    for (std::size_t k = 0; k < 11; ++k) in_[k * kBlock + count_] = values[k];
    if (++count_ == kBlock) flush();
  }
  // Orients the leaves added since the last block; call once every leaf is placed.
  void flush();

 private:
  float bend_;
  std::vector<Leaf>& leaves_;
  std::size_t first_ = 0, count_ = 0;  // the block: leaves_[first_, first_ + count_)
  std::vector<float> in_ = std::vector<float>(13 * kBlock), out_ = std::vector<float>(6 * kBlock);
};

}  // namespace arbor::generator::wp
