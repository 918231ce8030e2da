// The render fingerprint: the hash of everything that decides a render's pixels. It is stored
// with the film state (tracer::FilmHeader::fingerprint and ::settings, tracer/film_file.h) and in
// the finished EXR, and decides whether --resume may continue a state, merge may combine parts
// and a render may skip an image already made.
#pragma once

#include <optional>
#include <string>

#include "spec/scene_desc.h"

namespace arbor::app {

// The fingerprint (16 hex digits) of `scene` as the render sees it (its overrides applied), the
// command line's --time and --frame, and the OCIO config at `ocio`: every [render] key by its
// table at full precision (not threads: it changes no pixel), the outputs that change what is
// summed (a transparent sky, the compositing ids), the bytes of the scene file and of each of its
// inputs by their place in the scene (not how their paths are spelt), and the config's bytes.
// Sets `settings` to the same readable, "name value" items joined by "; ", so that a refused
// resume or merge can say which differ (tracer::settings_difference). InputError when an input
// cannot be read.
std::string render_fingerprint(const spec::SceneDesc& scene, std::optional<double> time,
                               std::optional<int> frame, const std::string& ocio,
                               std::string& settings);

}  // namespace arbor::app
