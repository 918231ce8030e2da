// The ground's material, from [ground] and, on a terrain, its soil and rock (docs/landscape.md).
#pragma once

#include "spec/scene_desc.h"
#include "materials/material.h"

namespace arbor::scene {

// Patched ground (materials/ground.h) when a cover, detail, stones, litter or a terrain asks for
// it; plain diffuse otherwise.
materials::Material ground_material(const spec::GroundDesc& ground,
                                    const spec::TerrainDesc& terrain);

}  // namespace arbor::scene
