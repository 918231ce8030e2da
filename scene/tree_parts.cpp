#include "scene/tree_parts.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace arbor::scene {

// The season's tint (materials/leaf_variation.h, LeafSeason): spring's from arbor's chlorophyll
// axis, ln tint += 0.35 · (1, 0.35, 0) (the variation's hue axis: a leaf with less chlorophyll);
// autumn's turns 85 % of the leaves towards the species' autumn colour, if it has one.
materials::LeafSeason leaf_season(generator::Season season, const std::optional<Rgb>& autumn,
                                  const Rgb& front) {
  materials::LeafSeason s;
  if (season == generator::Season::Spring) {
    s.spring = {static_cast<float>(std::exp(0.35)), static_cast<float>(std::exp(0.35 * 0.35)),
                1.0f};
  } else if (season == generator::Season::Autumn && autumn) {
    s.turned = 0.85f;
    for (int c = 0; c < 3; ++c) {
      const auto i = static_cast<std::size_t>(c);
      s.autumn[c] = static_cast<float>((*autumn)[i] / std::max(front[i], 1e-4));
    }
  }
  return s;
}

// TREE-MAKER's h0 and r0 (§III) from the skeleton's points, measured from the root stem's first
// point. A tree whose points all lie on one vertical line (r0 = 0), or at one height (h0 = 0),
// takes that measure from its geometry's bounds instead, so h/h0 and r/r0 stay finite.
TreeExtent tree_extent(const generator::Skeleton& sk, const generator::TreeGeometry& g) {
  TreeExtent e;
  for (const generator::Stem& stem : sk.stems) {
    if (stem.parent < 0 && stem.point_count > 0) {
      e.base = sk.points[stem.first_point].position;
      break;
    }
  }
  float h0 = 0.0f, r0 = 0.0f;
  for (const generator::SkeletonPoint& p : sk.points) {
    h0 = std::max(h0, p.position.z - e.base.z);
    r0 = std::max(r0, glm::length(glm::vec2(p.position - e.base)));
  }
  if (h0 <= 1e-6f) h0 = std::max(g.bounds_max.z - e.base.z, 1e-3f);
  if (r0 <= 1e-6f) {
    const glm::vec2 far = glm::max(glm::abs(glm::vec2(g.bounds_min - e.base)),
                                   glm::abs(glm::vec2(g.bounds_max - e.base)));
    r0 = std::max(glm::length(far), 1e-3f);
  }
  e.height = h0;
  e.radius = r0;
  return e;
}

}  // namespace arbor::scene
