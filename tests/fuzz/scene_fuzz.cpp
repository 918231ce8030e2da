// Fuzz target: scene files (TOML), read and validated (the OCIO names are checked later, by
// imaging/).
#include "fuzz_target.h"
#include "formats/scene_file.h"

ARBOR_FUZZ_TARGET({ arbor::formats::parse_scene(text, "fuzz/scene.toml"); })
