// Writing a film's outputs and state.
#include "tracer/render_output.h"

#include <cerrno>
#include <cstdio>
#include <unistd.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "imaging/image_output.h"
#include "imaging/treemaker_channels.h"

namespace arbor::tracer {

bool film_complete(const FilmHeader& h, const Film& film) {
  return film.window() == Window{0, 0, h.full_width, h.full_height} && film.pass_begin() == 0 &&
         film.next_pass() == h.plan.passes();
}

imaging::Image film_image(const FilmHeader& h, const Film& film) {
  imaging::Image img = film.image(film.extras());
  img.full_width = h.full_width;
  img.full_height = h.full_height;
  if (film.extras() > 0) img.extra_names = imaging::treemaker_channel_names();
  img.object_names = h.object_names;
  img.material_names = h.material_names;
  return img;
}

void write_render(const FilmHeader& h, const Film& film, const RenderWrite& what) {
  const imaging::OutputSpec& out = h.output;
  const imaging::Image img = film_image(h, film);
  if (!what.exr.empty()) {
    const std::string state = state_path(what.exr);
    if (what.keep_state || !film_complete(h, film)) {
      write_film_state(state, h, film);
    } else {
      // The finished render's state goes, and with it any temporary of it a killed writer left.
      remove_dead_temporaries(state);
      if (::unlink(state.c_str()) != 0 && errno != ENOENT) {
        throw RuntimeFailure("cannot remove the finished render's film state " + state);
      }
    }
    imaging::ExrMetadata meta;
    meta.scene = h.scene;
    meta.seed = h.seed;
    meta.integrator = name_of(h.integrator);
    meta.treemaker_weights = h.treemaker_weights;
    meta.exposure = h.exposure;
    meta.regularize = h.regularize;
    meta.lod_quality = h.lod_quality;
    meta.stats.seconds = h.seconds;
    meta.stats.nonfinite = h.nonfinite;
    meta.stats.rays = h.rays;
    meta.pass_spp = h.plan.pass_spp;
    meta.independent_passes = h.plan.independent;
    meta.passes_planned = h.plan.passes();
    meta.pass_begin = film.pass_begin();
    meta.pass_end = film.next_pass();
    meta.passes = film.next_pass() - film.pass_begin();
    meta.spp = h.plan.samples(film.pass_begin(), film.next_pass());
    meta.incomplete =
        what.stopped == StopReason::Interrupted || what.stopped == StopReason::InProgress;
    meta.stopped = name_of(what.stopped);
    meta.fingerprint = h.fingerprint;
    meta.noise_threshold = h.noise_threshold;
    meta.min_spp = h.min_spp;
    double total = 0;
    for (float s : img.samples) total += s;
    meta.mean_spp = img.samples.empty() ? 0.0 : total / double(img.samples.size());
    meta.interop_id = what.color->interop_id(h.output.colorspace);
    meta.chromaticities = what.color->chromaticities(h.output.colorspace);
    imaging::write_exr(img, out, meta, what.exr);
  }
  if (!what.png.empty()) imaging::write_png(img, out, *what.color, what.png);
}

}  // namespace arbor::tracer
