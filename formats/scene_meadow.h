// Internal to formats/: the scene file's [meadow] table (docs/rendering.md, "Meadow").
#pragma once

#include <toml++/toml.h>

#include "formats/scene_desc.h"
#include "formats/toml_reader.h"

namespace arbor::formats {

// Reads [meadow] into `m`: every key range-checked, unknown keys refused, at their position.
void read_meadow(const TomlReader& reader, const toml::table& t, MeadowDesc& m);

}  // namespace arbor::formats
