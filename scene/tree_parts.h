// Parts of a placed tree that build_scene takes from its growth and species: TREE-MAKER's
// extent of its skeleton, and its leaves' season.
#pragma once

#include <optional>

#include "common/math.h"
#include "generator/skeleton.h"
#include "generator/species.h"
#include "materials/leaf_variation.h"
#include "scene/scene.h"

namespace arbor::scene {

// The season's tint (materials/leaf_variation.h, LeafSeason): spring's from arbor's chlorophyll
// axis; autumn's turns 85 % of the leaves towards the species' autumn colour, if it has one.
materials::LeafSeason leaf_season(generator::Season season, const std::optional<Rgb>& autumn,
                                  const Rgb& front);

// TREE-MAKER's h0 and r0 (§III) from the skeleton's points, measured from the root stem's first
// point (bounds of the geometry where the skeleton has no height or no spread).
TreeExtent tree_extent(const generator::Skeleton& skeleton, const generator::TreeGeometry& g);

}  // namespace arbor::scene
