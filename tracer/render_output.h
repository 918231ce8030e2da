// Writing what a film holds: the EXR, the PNG and, when the image is not the whole finished
// render, the film state beside the EXR (film_file.h). Shared by `arbor render` (at the end, at
// checkpoints, on a signal) and `arbor merge`.
#pragma once

#include <string>

#include "imaging/color.h"
#include "imaging/image.h"
#include "tracer/film.h"
#include "tracer/film_file.h"
#include "tracer/render.h"

namespace arbor::tracer {

struct RenderWrite {
  std::string exr, png;                           // empty: not written
  const imaging::ColorPipeline* color = nullptr;  // for the PNG
  StopReason stopped = StopReason::None;
  // A work unit (--passes, --crop) keeps its film state even when it holds the whole render:
  // its merge reads every part's state, and a plan of one unit is such a part.
  bool keep_state = false;
};

// True when the film holds every pass of the whole image: nothing to resume or merge.
bool film_complete(const FilmHeader& header, const Film& film);

// The image of the film, its whole-image size set.
imaging::Image film_image(const FilmHeader& header, const Film& film);

// Writes the state (unless complete and not kept; a stale one is then removed), the EXR, then the
// PNG, each
// atomically. The state goes first: a kill between the writes leaves a state at least as far
// along as the EXR, which is what --resume continues from.
void write_render(const FilmHeader& header, const Film& film, const RenderWrite& what);

}  // namespace arbor::tracer
