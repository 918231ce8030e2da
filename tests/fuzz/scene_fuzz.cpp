// Fuzz target: scene files (TOML), read and validated (the OCIO config included).
#include "fuzz_target.h"
#include "tracer/scene_desc.h"

ARBOR_FUZZ_TARGET({ arbor::trace::parse_scene(text, "fuzz/scene.toml"); })
