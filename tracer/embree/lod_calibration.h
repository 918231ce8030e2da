// Level of detail's leaf area, calibrated by the crown's transmission (docs/rendering.md, "Level
// of detail"). Keeping one leaf of each mass of four at twice the size keeps the crown's leaf area
// but not its cover: the four leaves of a mass overlap one another, the enlarged survivor
// overlaps nothing, so the thinned crown stops more light (measured: +3 % of cover on a Quaking
// Aspen seen from the side, +5 to 7 % of image mean on a forest at 2 km). The calibration finds,
// for each prototype, the share of the leaf area the survivors need for the crown to stop as much
// light as at full detail, by tracing the prototype itself.
#pragma once

#include <vector>

#include "generator/geometry/tree_geometry.h"
#include "scene/lod.h"
#include "tracer/embree/embree_device.h"

struct RTCSceneTy;

namespace arbor::tracer {

// The factor α by which the survivors' total leaf area is the full crown's when one leaf in four
// is kept and, as far away, no limb but the trunk (kept area = α × full area; the leaves also
// make up for the branches' cover): the α at which parallel rays from nine directions (three
// elevations, three azimuths, a 48 × 48 grid each over the crown's bounds) stop as many as at
// full detail, found by bisection on the leaf scale in [1, kLodMaxLeafScale]. `prototype` is the
// prototype's Embree scene, built with cards enlarged by kLodMaxLeafScale and leaf thinning; its
// filters read the instance with top-level id 0 from `instances`, whose first entry is borrowed
// for the calibration and restored. Deterministic.
double calibrate_leaf_area(const EmbreeDevice& device, RTCSceneTy* prototype,
                           const generator::TreeGeometry& geometry,
                           std::vector<scene::InstanceLod>& instances);

// The leaf scale of a tree that keeps `kept` of its `total` leaves, for a prototype whose
// calibrated α is `alpha` (α interpolated linearly in the kept fraction from 1 with every leaf
// kept to `alpha` with one in four): √(α(f) / f), at most kLodMaxLeafScale.
float calibrated_leaf_scale(double alpha, std::uint32_t kept, std::uint32_t total);

}  // namespace arbor::tracer
