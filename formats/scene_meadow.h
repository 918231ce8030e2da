// Internal to formats/: the scene file's [meadow] table (docs/rendering.md, "Meadow").
#pragma once

#include "spec/scene_desc.h"

namespace arbor::formats {

// The rules across [meadow]'s keys (each key's range is checked as it is read): a blade creates
// no light, and the meadow's blades, tiles and distinct blades are bounded. InputError at the
// table.
void check_meadow(const spec::MeadowDesc& m);

}  // namespace arbor::formats
