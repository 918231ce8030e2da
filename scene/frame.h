// A frame of a scene's [animation]: its clock, its seed and its frame number in the outputs.
#pragma once

#include <optional>

#include "spec/scene_desc.h"

namespace arbor::scene {

// Applies `frame` (when given) to the scene: the clock, the frame's seed unless pinned, the
// frame number in place of the '#' run in every output path. InputError when the scene has no
// [animation], the frame is outside it, or an output names a frame number but no frame is given.
void apply_frame(spec::SceneDesc& scene, std::optional<int> frame);

}  // namespace arbor::scene
