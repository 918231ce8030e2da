// Weber & Penn §5's equations, as the paper gives them.
#include "scene/lod.h"

#include <algorithm>
#include <cmath>

namespace arbor::scene {

double calibrated_range(double range, int image_height, double vertical_fov_degrees) {
  return range * 1000.0 / static_cast<double>(image_height) * vertical_fov_degrees / 60.0;
}

LodScale lod_scale(double quality, generator::Season season, bool evergreen) {
  LodScale l;
  const bool spring = season == generator::Season::Spring;
  l.s = evergreen || !spring ? quality / 2.0 : quality;
  l.d = spring ? 100.0 : 200.0;
  return l;
}

std::array<double, kLodLevels> lod_numbers(double r2, const LodScale& scale) {
  const double s = scale.s, d = scale.d;
  const auto clamp = [](double v, double size) { return std::clamp(v, 0.0, size); };
  std::array<double, kLodLevels> n{};
  // Level 0: polygons below r2 = 800, lines beyond r2 = 100: the trunk is always drawn.
  n[kLodTrunk] = kLodMassSize[kLodTrunk];
  // Level 1: all lines below 200s; 16 · [2.2 − 1.2 (r2 / 200s)^0.3] to 2000s; none beyond.
  const double m1 = kLodMassSize[kLodMainBranches];
  n[kLodMainBranches] = r2 < 200.0 * s ? m1
                        : r2 < 2000.0 * s
                            ? clamp(m1 * (2.2 - 1.2 * std::pow(r2 / (200.0 * s), 0.3)), m1)
                            : 0.0;
  // Level 2: all lines below 100s; 16 · [2 − (r2 / 100s)^0.5] to 500s; none beyond.
  const double m2 = kLodMassSize[kLodBranches];
  n[kLodBranches] = r2 < 100.0 * s   ? m2
                    : r2 < 500.0 * s ? clamp(m2 * (2.0 - std::sqrt(r2 / (100.0 * s))), m2)
                                     : 0.0;
  // Leaves: all points below d; 4 · [1.5 − r2 / 2d] beyond, at least 1.
  const double m3 = kLodMassSize[kLodLeaves];
  n[kLodLeaves] = r2 < d ? m3 : std::max(1.0, m3 * (1.5 - r2 / (2.0 * d)));
  return n;
}

LodKeep lod_keep(double number, std::uint32_t mass_size, std::uint32_t total) {
  LodKeep k;
  k.size = mass_size;
  number = std::clamp(number, 0.0, static_cast<double>(mass_size));
  k.whole = static_cast<std::uint32_t>(std::floor(number));
  const std::uint32_t masses = (total + mass_size - 1) / mass_size;
  // The paper's "if mass < change" with change = masses · (number − whole).
  k.change = static_cast<std::uint32_t>(std::ceil(masses * (number - k.whole)));
  if (k.whole == mass_size) k.change = 0;
  return k;
}

std::uint32_t lod_kept(const LodKeep& keep, std::uint32_t total) {
  std::uint32_t kept = 0;
  const std::uint32_t masses = (total + keep.size - 1) / keep.size;
  for (std::uint32_t m = 0; m < masses; ++m) {
    const std::uint32_t in_mass = std::min(keep.size, total - m * keep.size);
    const std::uint32_t n = keep.whole + (m < keep.change ? 1u : 0u);
    kept += std::min(in_mass, n);
  }
  return kept;
}

InstanceLod instance_lod(double r2, const LodScale& scale,
                         const std::array<std::uint32_t, kLodLevels>& items) {
  InstanceLod lod;
  lod.active = true;
  lod.r2 = r2;
  const std::array<double, kLodLevels> n = lod_numbers(r2, scale);
  for (int l = 0; l < kLodLevels; ++l) {
    const auto i = static_cast<std::size_t>(l);
    lod.keep[i] = lod_keep(n[i], kLodMassSize[i], items[i]);
  }
  // The crown's leaf area kept: each survivor's area × total / kept.
  const std::uint32_t leaves = items[kLodLeaves];
  const std::uint32_t kept = lod_kept(lod.keep[kLodLeaves], leaves);
  if (leaves > 0 && kept > 0 && kept < leaves) {
    lod.leaf_scale = std::min(kLodMaxLeafScale,
                              static_cast<float>(std::sqrt(static_cast<double>(leaves) / kept)));
  }
  return lod;
}

}  // namespace arbor::scene
