// Work units of one render (--passes ranges, --crop windows) folded into the film the single
// render gives, bit for bit (docs/farm.md).
#pragma once

#include <string>
#include <vector>

#include "tracer/film_file.h"

namespace arbor::tracer {

// One part: the EXR it was written as (for messages) and its film state, read.
struct FilmPart {
  std::string exr;
  FilmFile file;
  int begin() const { return file.film->pass_begin(); }
  int end() const { return file.film->next_pass(); }
  const Window& window() const { return file.film->window(); }
};

// "pass 3" or "passes 3 to 7", for messages.
std::string passes_text(int begin, int end);

// The film of the parts together: its window the parts' bounding box, its passes theirs, each
// pixel folded in pass order; its header the first part's with the seconds, rays and non-finite
// counts summed. InputError naming the part when the parts are not of one render, overlap, or
// leave a gap. The parts must be finished (end() == their header's pass_end).
FilmFile merge_film_parts(std::vector<FilmPart> parts);

}  // namespace arbor::tracer
