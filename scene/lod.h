// Level of detail at range: Weber & Penn §5, "Degradation at range", for a path tracer
// (docs/rendering.md, "Level of detail"). Every item of a tree (a limb's curve segment, a leaf) has
// a level — trunk, main branches, other branches, leaves — and an index among its level's items in
// the order it was made. Items fall into masses of 16 (stems) or 4 (leaves); at calibrated range
// r2 a level keeps the first `number` items of each mass, a fractional number keeping one more in
// the first masses (the paper's loop). An item's fate depends only on its index, so as a tree
// comes closer it gains items one at a time and never loses one (no "resolution waves").
#pragma once

#include <array>
#include <cstdint>

#include "generator/species.h"

namespace arbor::scene {

// The paper's items: level-0 stems, level-1 stems, stems of level 2 and deeper, leaves.
enum LodLevel : std::uint8_t {
  kLodTrunk = 0,
  kLodMainBranches = 1,
  kLodBranches = 2,
  kLodLeaves = 3
};
inline constexpr int kLodLevels = 4;
// The paper's mass sizes: 16 for every stem level, 4 for leaves.
inline constexpr std::array<std::uint32_t, kLodLevels> kLodMassSize = {16, 16, 16, 4};
// Surviving leaves grow by at most this much in length (area × 4): the paper keeps at least one
// leaf of each mass of 4.
inline constexpr float kLodMaxLeafScale = 2.0f;

// What the camera gives: r2 = range · 1000 / image height · vertical fov / 60 (the paper's
// calibration of range for image size and a telephoto lens).
double calibrated_range(double range, int image_height, double vertical_fov_degrees);

// The paper's general scaling factors from the quality factor: s = quality / 2 for an evergreen
// tree or in summer and autumn, quality otherwise (spring); d = 100 in spring, 200 otherwise.
struct LodScale {
  double s = 0.5, d = 200.0;
};
LodScale lod_scale(double quality, generator::Season season, bool evergreen);

// The number of items of each mass a level keeps at calibrated range r2, in [0, mass size]: the
// paper's curve fits, taking for each level the larger of its polygon and its line or point
// numbers (a path tracer draws a kept item as itself however far away; docs/rendering.md).
std::array<double, kLodLevels> lod_numbers(double r2, const LodScale& scale);

// One level's survivors, for a tree with `total` items of that level: item k, in mass k / size at
// place k % size, survives when its place < whole, or = whole in the first `change` masses.
struct LodKeep {
  std::uint32_t size = 16, whole = 16, change = 0;
  bool keeps(std::uint32_t item) const {
    const std::uint32_t place = item % size;
    return place < whole || (place == whole && item / size < change);
  }
};
LodKeep lod_keep(double number, std::uint32_t mass_size, std::uint32_t total);
// How many of `total` items survive.
std::uint32_t lod_kept(const LodKeep& keep, std::uint32_t total);

// One placed tree's level of detail: what each level keeps, and how much each surviving leaf is
// enlarged (in length) so that the crown keeps its leaf area.
struct InstanceLod {
  bool active = false;  // [render] lod is on (else everything is kept)
  double r2 = 0.0;
  std::array<LodKeep, kLodLevels> keep{};
  float leaf_scale = 1.0f;
  // Whether item `item` of level `level` is kept; levels past the last (such as TREE-MAKER's
  // leaf lines, generator::kNoLod) are never thinned.
  bool keeps(std::uint8_t level, std::uint32_t item) const {
    return level >= kLodLevels || keep[level].keeps(item);
  }
  bool thins_stems() const {
    return keep[kLodMainBranches].whole < keep[kLodMainBranches].size ||
           keep[kLodBranches].whole < keep[kLodBranches].size;
  }
};
// A tree with `items` items per level at calibrated range r2.
InstanceLod instance_lod(double r2, const LodScale& scale,
                         const std::array<std::uint32_t, kLodLevels>& items);

}  // namespace arbor::scene
