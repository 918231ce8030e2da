// Reading a scene file (docs/scene-format.md) into its plain data (spec/scene_desc.h), by the key
// tables (formats/scene_keys.h), and what is generated from those tables.
#pragma once

#include <string>

#include "spec/scene_desc.h"

namespace arbor::formats {

// Reads and validates a scene file: unknown keys and out-of-range values are InputErrors with
// their position; relative paths are resolved against the scene file's folder. Every input the
// scene uses (scene_inputs) must be a readable regular file: else InputError at the key naming it.
spec::SceneDesc load_scene(const std::string& path);
spec::SceneDesc parse_scene(const std::string& text, const std::string& path);

// Every [render] key and its value at full precision, "name value" items joined by "; "
// ("width 480; height 360; spp 256; …"): what a render's fingerprint holds of its settings.
std::string render_settings_text(const spec::RenderSettings& render);

// The scene file's key reference, as docs/scene-format.md holds it (Markdown, generated from the
// key tables that the reader reads by).
std::string scene_key_reference();

}  // namespace arbor::formats
