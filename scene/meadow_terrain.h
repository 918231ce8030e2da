// Internal to scene/: a meadow laid on a terrain (scene/meadow.h, grow_meadow).
#pragma once

#include <vector>

#include "scene/meadow.h"

namespace arbor::scene {

// Tiles of side `side` cut along the diagonal into their two triangles, each at the four
// densities kept: tiles[(k · 2 + half) · 4 + level].
std::vector<GrassTile> cut_tiles(const std::vector<GrassTile>& whole, double side);

// The placements of the cut tiles in `m` over the cells of `terrain` the area of `d` touches.
void place_on_terrain(const spec::MeadowDesc& d, const Terrain& terrain, Meadow& m);

}  // namespace arbor::scene
