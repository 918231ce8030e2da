// pbrt-v4 export of a tree: limbs as curves, trunk and leaves as triangle meshes.
#pragma once

#include <string>

#include "generator/species.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::gen {

// Writes a file to `Include` inside a pbrt-v4 world block: each curve segment as a cubic Bézier
// "curve" of type "cylinder" (the exact Hermite segment converted to Bézier form, width = 2 ×
// radius at each end), displaced trunk grids as "trianglemesh" with normals, leaves as one
// "trianglemesh" with uv under a "diffusetransmission" material. Atomic.
void write_pbrt(const TreeGeometry& geometry, const BarkLook& bark, const LeafLook& leaf,
                const std::string& path);

}  // namespace arbor::gen
