// `arbor merge`: read every part's film state, check that they are one render and tile its
// passes and pixels exactly once, fold them in pass order, write.
#include "tracer/merge_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/strings.h"
#include "imaging/color.h"
#include "tracer/film_file.h"
#include "tracer/render_output.h"

namespace arbor::trace {

namespace {

struct Part {
  std::string exr;
  FilmFile file;
  int begin() const { return file.film->pass_begin(); }
  int end() const { return file.film->next_pass(); }
  const Window& window() const { return file.film->window(); }
};

std::string passes_text(int begin, int end) {
  return end - begin == 1 ? "pass " + std::to_string(begin)
                          : "passes " + std::to_string(begin) + " to " + std::to_string(end - 1);
}

// InputError unless `b` is a part of the same render as `a`.
void require_same_render(const Part& a, const Part& b) {
  const FilmHeader &ha = a.file.header, &hb = b.file.header;
  if (hb.fingerprint != ha.fingerprint) {
    throw InputError({b.exr, 0, 0}, "is not a part of the same render as " + a.exr + ": it was rendered from " +
                                        hb.scene + " with other settings or inputs (" +
                                        settings_difference(ha.settings, hb.settings, "in " + a.exr, "in this part") + ")");
  }
  if (hb.full_width != ha.full_width || hb.full_height != ha.full_height || hb.plan.spp != ha.plan.spp ||
      hb.plan.pass_spp != ha.plan.pass_spp || hb.plan.independent != ha.plan.independent || b.file.film->extras() != a.file.film->extras() ||
      b.file.film->keeps_ids() != a.file.film->keeps_ids() || hb.object_names != ha.object_names ||
      hb.aovs != ha.aovs || hb.colorspace != ha.colorspace || hb.pixel_type != ha.pixel_type) {
    throw InputError({b.exr, 0, 0}, "has other image settings (size, samples, AOVs or colour space) than " + a.exr);
  }
}

}  // namespace

int merge_command(const MergeRequest& req) {
  if (req.parts.empty()) throw InputError({}, "merge needs at least one part");
  if (!ends_with(req.exr, ".exr")) throw InputError({}, "the merged output must end in .exr: " + req.exr);
  if (!req.png.empty() && !ends_with(req.png, ".png")) throw InputError({}, "--png must end in .png: " + req.png);
  std::vector<std::string> inputs;
  for (const std::string& p : req.parts) {
    inputs.push_back(p);
    inputs.push_back(state_path(p));
  }
  refuse_overwriting("the merged EXR", req.exr, inputs);
  refuse_overwriting("the merged EXR's film state", state_path(req.exr), inputs, {req.exr});
  if (!req.png.empty()) refuse_overwriting("the merged PNG", req.png, inputs, {req.exr, state_path(req.exr)});
  for (const std::string& out : {req.exr, req.png}) {
    if (!out.empty()) prepare_output_folder(out);
  }

  // Every part there and finished, or one error naming each that is not (a farm re-runs those).
  std::vector<Part> parts;
  std::vector<std::string> missing, incomplete;
  for (const std::string& p : req.parts) {
    const std::string state = state_path(p);
    std::error_code ec;
    if (!std::filesystem::exists(p, ec) || !std::filesystem::exists(state, ec)) {
      missing.push_back(p);
      continue;
    }
    parts.push_back({p, read_film_state(state)});
    const Part& part = parts.back();
    if (part.end() < part.file.header.pass_end) {
      incomplete.push_back(p + " (holds " + (part.end() > part.begin() ? passes_text(part.begin(), part.end()) : "no pass") +
                           " of its " + passes_text(part.begin(), part.file.header.pass_end) + ")");
    }
  }
  if (!missing.empty() || !incomplete.empty()) {
    std::string text = std::to_string(missing.size() + incomplete.size()) + " of the " + std::to_string(req.parts.size()) +
                       " parts cannot be merged; run those units again:";
    for (const std::string& m : missing) text += "\n  missing: " + m + (std::filesystem::exists(m) ? " (its film state " + state_path(m) + " is not there)" : "");
    for (const std::string& m : incomplete) text += "\n  incomplete: " + m + " (stopped; --resume finishes it)";
    throw InputError({}, text);
  }
  for (std::size_t i = 1; i < parts.size(); ++i) require_same_render(parts.front(), parts[i]);
  // Pass order, whatever the order of the arguments.
  std::stable_sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.begin() < b.begin(); });
  const FilmHeader& first = parts.front().file.header;
  Window box = parts.front().window();
  int begin = parts.front().begin(), end = parts.front().end();
  for (const Part& p : parts) {
    box = {std::min(box.x0, p.window().x0), std::min(box.y0, p.window().y0), std::max(box.x1, p.window().x1),
           std::max(box.y1, p.window().y1)};
    begin = std::min(begin, p.begin());
    end = std::max(end, p.end());
  }

  // Every pixel of the box must hold passes [begin, end), each exactly once.
  Film merged(box, parts.front().file.film->extras(), begin, begin > 0, parts.front().file.film->keeps_ids());
  merged.set_next_pass(end);
  const std::size_t r = merged.record_size(), stride = merged.sum_stride();
  if (merged.keeps_records()) merged.records().assign(static_cast<std::size_t>(end - begin) * r * box.pixels(), 0.0);
  for (int y = box.y0; y < box.y1; ++y) {
    for (int x = box.x0; x < box.x1; ++x) {
      const std::size_t q = static_cast<std::size_t>(y - box.y0) * box.width() + (x - box.x0);
      int reached = begin;
      const Part* previous = nullptr;
      for (const Part& part : parts) {
        const Window& w = part.window();
        if (x < w.x0 || x >= w.x1 || y < w.y0 || y >= w.y1) continue;
        auto pixel = [&] { return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")"; };
        if (part.begin() < reached) {
          throw InputError({part.exr, 0, 0}, "overlaps " + previous->exr + ": both hold " +
                                                 passes_text(part.begin(), std::min(reached, part.end())) + " of " + pixel());
        }
        if (part.begin() > reached) {
          throw InputError({part.exr, 0, 0}, "leaves a gap: no part holds " + passes_text(reached, part.begin()) +
                                                 " of " + pixel());
        }
        const Film& film = *part.file.film;
        const std::size_t p = static_cast<std::size_t>(y - w.y0) * w.width() + (x - w.x0);
        if (!film.keeps_records()) {
          // Passes from 0: its running state is where the render stood after them.
          merged.states()[q] = film.state(p);
          std::copy_n(&film.sums()[p * stride], stride, &merged.sums()[q * stride]);
        } else {
          for (int pass = part.begin(); pass < part.end(); ++pass) {
            const double* rec = &film.records()[static_cast<std::size_t>(pass - part.begin()) * r * w.pixels() + p * r];
            merged.fold_record(q, rec);
            if (merged.keeps_records()) {
              std::copy_n(rec, r, &merged.records()[static_cast<std::size_t>(pass - begin) * r * box.pixels() + q * r]);
            }
          }
        }
        reached = part.end();
        previous = &part;
      }
      if (reached != end) {
        throw InputError({}, "the parts leave a gap: none holds " + passes_text(reached, end) + " of pixel (" +
                                 std::to_string(x) + ", " + std::to_string(y) + ")" +
                                 (reached == begin ? ", which lies in no part's window" : ""));
      }
    }
  }

  FilmHeader header = first;
  header.pass_end = end;
  header.seconds = 0;
  header.nonfinite = header.rays = 0;
  for (const Part& p : parts) {
    header.seconds += p.file.header.seconds;
    header.nonfinite += p.file.header.nonfinite;
    header.rays += p.file.header.rays;
  }
  const ColorPipeline color(req.ocio_config);
  write_render(header, merged, {req.exr, req.png, &color, ""});
  std::fprintf(stderr, "arbor: merged %zu parts: %dx%d at (%d, %d), %s of %d%s\n", parts.size(), box.width(),
               box.height(), box.x0, box.y0, passes_text(begin, end).c_str(), first.plan.passes(),
               film_complete(header, merged) ? " (the whole render)" : "");
  std::fprintf(stderr, "arbor: wrote %s\n", req.exr.c_str());
  if (!req.png.empty()) std::fprintf(stderr, "arbor: wrote %s\n", req.png.c_str());
  return 0;
}

}  // namespace arbor::trace
