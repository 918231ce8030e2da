// The film state file, `<exr>.state` beside a render's EXR: everything needed to continue the
// render exactly (--resume) or to merge it with other parts (arbor merge): each pixel's running
// sums in double precision and, for a pass range that does not start at pass 0, each pass's own
// results. Written atomically with the EXR whenever the image is not the whole, finished render.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "imaging/output_spec.h"
#include "scene/render_input.h"
#include "tracer/film.h"

namespace arbor::tracer {

struct FilmHeader {
  std::string fingerprint;  // of the scene, its inputs and the settings that decide the pixels
  std::string settings;     // the same, readable: "name value" items joined by "; "
  std::string scene;        // the scene file, for messages
  int full_width = 0, full_height = 0;
  PassPlan plan;
  int pass_end = 0;  // the pass range's end: the part renders [film.pass_begin(), pass_end)
  double noise_threshold = 0;
  int min_spp = 0;
  double seconds = 0;  // render time spent so far
  std::uint64_t nonfinite = 0, rays = 0;
  // What the outputs are written with (a merge writes them again without the scene).
  spec::Integrator integrator = spec::Integrator::Path;
  std::uint64_t seed = 0;
  imaging::OutputSpec output;
  std::string treemaker_weights;
  // The stops the samples were exposed by, as arbor:exposure says them ("1.5", or "1.390625
  // (metered)" for exposure = "auto"); empty in a state file written before it was kept.
  std::string exposure;
  bool regularize = false;   // [render] regularize (absent from older state files: off)
  double lod_quality = 0.0;  // [render] lod_quality with lod on; 0: off (absent: off)
  // The compositing ids' names (Scene::object_names, material_names).
  std::vector<std::string> object_names, material_names;
};

struct FilmFile {
  FilmHeader header;
  std::unique_ptr<Film> film;
};

// `<exr>.state`.
std::string state_path(const std::string& exr);

// Writes atomically (RuntimeFailure when it cannot).
void write_film_state(const std::string& path, const FilmHeader& header, const Film& film);

// InputError naming the file when it is missing, not a film state, or truncated.
FilmFile read_film_state(const std::string& path);

// Which settings items differ between two renders' `settings`, as "spp 64 in A, 128 in B; input
// aspen.toml has other contents" with `in_a`, `in_b` naming them; "the same settings" when none
// does.
std::string settings_difference(const std::string& a, const std::string& b, const std::string& in_a,
                                const std::string& in_b);

// A 64-bit FNV-1a hash of `text` continued from `hash`, as 16 hex digits by fingerprint_hex.
std::uint64_t fnv1a(const std::string& text, std::uint64_t hash = 0xcbf29ce484222325ull);
std::string fingerprint_hex(std::uint64_t hash);

// A double with every digit it needs to read back the same (%.17g): the state file's numbers, the
// EXR's arbor:exposure.
std::string number_text(double v);

}  // namespace arbor::tracer
