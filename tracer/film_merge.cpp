// Merging parts: check that they are one render and tile its passes and pixels exactly once,
// fold them in pass order.
#include "tracer/film_merge.h"

#include <algorithm>
#include <memory>

#include "common/error.h"

namespace arbor::tracer {

namespace {

// InputError unless `b` is a part of the same render as `a`.
void require_same_render(const FilmPart& a, const FilmPart& b) {
  const FilmHeader &ha = a.file.header, &hb = b.file.header;
  if (hb.fingerprint != ha.fingerprint) {
    throw InputError(
        {b.exr, 0, 0},
        "is not a part of the same render as " + a.exr + ": it was rendered from " + hb.scene +
            " with other settings or inputs (" +
            settings_difference(ha.settings, hb.settings, "in " + a.exr, "in this part") + ")");
  }
  if (hb.full_width != ha.full_width || hb.full_height != ha.full_height ||
      hb.plan.spp != ha.plan.spp || hb.plan.pass_spp != ha.plan.pass_spp ||
      hb.plan.independent != ha.plan.independent ||
      b.file.film->extras() != a.file.film->extras() ||
      b.file.film->keeps_ids() != a.file.film->keeps_ids() || hb.object_names != ha.object_names ||
      hb.output.aovs != ha.output.aovs || hb.output.colorspace != ha.output.colorspace ||
      hb.output.pixel_type != ha.output.pixel_type) {
    throw InputError(
        {b.exr, 0, 0},
        "has other image settings (size, samples, AOVs or colour space) than " + a.exr);
  }
}

// Folds every part holding pixel (x, y) into `merged`'s pixel `q`, checking that they hold
// passes [begin, end) of it exactly once.
void fold_pixel(const std::vector<FilmPart>& parts, int x, int y, std::size_t q, int begin, int end,
                Film& merged) {
  const Window& box = merged.window();
  const std::size_t r = merged.record_size(), stride = merged.sum_stride();
  int reached = begin;
  const FilmPart* previous = nullptr;
  for (const FilmPart& part : parts) {
    const Window& w = part.window();
    if (x < w.x0 || x >= w.x1 || y < w.y0 || y >= w.y1) continue;
    auto pixel = [&] { return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")"; };
    if (part.begin() < reached) {
      throw InputError({part.exr, 0, 0},
                       "overlaps " + previous->exr + ": both hold " +
                           passes_text(part.begin(), std::min(reached, part.end())) + " of " +
                           pixel());
    }
    if (part.begin() > reached) {
      throw InputError({part.exr, 0, 0}, "leaves a gap: no part holds " +
                                             passes_text(reached, part.begin()) + " of " + pixel());
    }
    const Film& film = *part.file.film;
    const std::size_t p = static_cast<std::size_t>(y - w.y0) * w.width() + (x - w.x0);
    if (!film.keeps_records()) {
      // Passes from 0: its running state is where the render stood after them.
      merged.states()[q] = film.state(p);
      std::copy_n(&film.sums()[p * stride], stride, &merged.sums()[q * stride]);
    } else {
      for (int pass = part.begin(); pass < part.end(); ++pass) {
        const double* rec =
            &film.records()[static_cast<std::size_t>(pass - part.begin()) * r * w.pixels() + p * r];
        merged.fold_record(q, rec);
        if (merged.keeps_records()) {
          std::copy_n(
              rec, r,
              &merged.records()[static_cast<std::size_t>(pass - begin) * r * box.pixels() + q * r]);
        }
      }
    }
    reached = part.end();
    previous = &part;
  }
  if (reached != end) {
    throw InputError({}, "the parts leave a gap: none holds " + passes_text(reached, end) +
                             " of pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")" +
                             (reached == begin ? ", which lies in no part's window" : ""));
  }
}

}  // namespace

std::string passes_text(int begin, int end) {
  return end - begin == 1 ? "pass " + std::to_string(begin)
                          : "passes " + std::to_string(begin) + " to " + std::to_string(end - 1);
}

FilmFile merge_film_parts(std::vector<FilmPart> parts) {
  if (parts.empty()) throw InputError({}, "merge needs at least one part");
  for (std::size_t i = 1; i < parts.size(); ++i) require_same_render(parts.front(), parts[i]);
  // Pass order, whatever the order of the arguments.
  std::stable_sort(parts.begin(), parts.end(),
                   [](const FilmPart& a, const FilmPart& b) { return a.begin() < b.begin(); });
  Window box = parts.front().window();
  int begin = parts.front().begin(), end = parts.front().end();
  for (const FilmPart& p : parts) {
    box = {std::min(box.x0, p.window().x0), std::min(box.y0, p.window().y0),
           std::max(box.x1, p.window().x1), std::max(box.y1, p.window().y1)};
    begin = std::min(begin, p.begin());
    end = std::max(end, p.end());
  }

  // Every pixel of the box must hold passes [begin, end), each exactly once.
  FilmFile merged;
  merged.film = std::make_unique<Film>(box, parts.front().file.film->extras(), begin, begin > 0,
                                       parts.front().file.film->keeps_ids());
  Film& film = *merged.film;
  film.set_next_pass(end);
  if (film.keeps_records()) {
    film.records().assign(static_cast<std::size_t>(end - begin) * film.record_size() * box.pixels(),
                          0.0);
  }
  for (int y = box.y0; y < box.y1; ++y) {
    for (int x = box.x0; x < box.x1; ++x) {
      fold_pixel(parts, x, y, static_cast<std::size_t>(y - box.y0) * box.width() + (x - box.x0),
                 begin, end, film);
    }
  }

  merged.header = parts.front().file.header;
  merged.header.pass_end = end;
  merged.header.seconds = 0;
  merged.header.nonfinite = merged.header.rays = 0;
  for (const FilmPart& p : parts) {
    merged.header.seconds += p.file.header.seconds;
    merged.header.nonfinite += p.file.header.nonfinite;
    merged.header.rays += p.file.header.rays;
  }
  return merged;
}

}  // namespace arbor::tracer
