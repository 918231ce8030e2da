// `arbor merge`: check the outputs, read every part's film state, merge (tracer/film_merge.h),
// write, report.
#include "app/commands/merge.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/strings.h"
#include "imaging/color.h"
#include "tracer/film_merge.h"
#include "tracer/render_output.h"

namespace arbor::app {

using tracer::Film;
using tracer::film_complete;
using tracer::FilmFile;
using tracer::FilmHeader;
using tracer::FilmPart;
using tracer::passes_text;
using tracer::read_film_state;
using tracer::state_path;
using tracer::StopReason;
using tracer::Window;
using tracer::write_render;

namespace {

void check_outputs(const MergeRequest& req) {
  if (req.parts.empty()) throw InputError({}, "merge needs at least one part");
  if (!ends_with(req.exr, ".exr"))
    throw InputError({}, "the merged output must end in .exr: " + req.exr);
  if (!req.png.empty() && !ends_with(req.png, ".png"))
    throw InputError({}, "--png must end in .png: " + req.png);
  std::vector<std::string> inputs;
  for (const std::string& p : req.parts) {
    inputs.push_back(p);
    inputs.push_back(state_path(p));
  }
  refuse_overwriting("the merged EXR", req.exr, inputs);
  refuse_overwriting("the merged EXR's film state", state_path(req.exr), inputs, {req.exr});
  if (!req.png.empty())
    refuse_overwriting("the merged PNG", req.png, inputs, {req.exr, state_path(req.exr)});
}

// Every part there and finished, or one error naming each that is not (a farm re-runs those).
std::vector<FilmPart> read_parts(const std::vector<std::string>& paths) {
  std::vector<FilmPart> parts;
  std::vector<std::string> missing, incomplete;
  for (const std::string& p : paths) {
    const std::string state = state_path(p);
    std::error_code ec;
    if (!std::filesystem::exists(p, ec) || !std::filesystem::exists(state, ec)) {
      missing.push_back(p);
      continue;
    }
    parts.push_back({p, read_film_state(state)});
    const FilmPart& part = parts.back();
    if (part.end() < part.file.header.pass_end) {
      incomplete.push_back(
          p + " (holds " +
          (part.end() > part.begin() ? passes_text(part.begin(), part.end()) : "no pass") +
          " of its " + passes_text(part.begin(), part.file.header.pass_end) + ")");
    }
  }
  if (!missing.empty() || !incomplete.empty()) {
    std::string text = std::to_string(missing.size() + incomplete.size()) + " of the " +
                       std::to_string(paths.size()) +
                       " parts cannot be merged; run those units again:";
    for (const std::string& m : missing)
      text += "\n  missing: " + m +
              (std::filesystem::exists(m) ? " (its film state " + state_path(m) + " is not there)"
                                          : "");
    for (const std::string& m : incomplete)
      text += "\n  incomplete: " + m + " (stopped; --resume finishes it)";
    throw InputError({}, text);
  }
  return parts;
}

// InputError unless the merged film is the whole render: a forgotten tile or pass group is named
// before anything is written.
void check_whole(const FilmFile& merged, std::size_t count) {
  const FilmHeader& h = merged.header;
  const Film& film = *merged.film;
  if (film_complete(h, film)) return;
  const Window& box = film.window();
  std::string lacks;
  if (!(box == Window{0, 0, h.full_width, h.full_height})) {
    lacks = "the window " + std::to_string(box.x0) + "," + std::to_string(box.y0) + "," +
            std::to_string(box.x1) + "," + std::to_string(box.y1) + " of the " +
            std::to_string(h.full_width) + "x" + std::to_string(h.full_height) + " image";
  }
  if (film.pass_begin() != 0 || film.next_pass() != h.plan.passes()) {
    lacks += (lacks.empty() ? "" : ", and ") + passes_text(film.pass_begin(), film.next_pass()) +
             " of the render's " + passes_text(0, h.plan.passes());
  }
  throw InputError({}, (count == 1 ? std::string("the part covers only ")
                                   : "the " + std::to_string(count) + " parts cover only ") +
                           lacks +
                           "; give the parts that are missing, or --partial to write what "
                           "they cover (with its film state, to merge the rest into later)");
}

}  // namespace

CLI::App* add_merge_command(CLI::App& app, MergeRequest& merge) {
  CLI::App* cmd = app.add_subcommand("merge",
                                     "Combine work units of one render (--passes ranges, --crop "
                                     "windows) into its image, bit for bit");
  cmd->add_option(
         "PARTS", merge.parts,
         "the parts' EXRs, in any order (each with its film state PART.exr.state beside it)")
      ->required();
  cmd->add_option("-o,--output", merge.exr, "the merged EXR")->required();
  cmd->add_option("--png", merge.png, "also write a PNG of it through the display view");
  cmd->add_flag(
      "--partial", merge.partial,
      "write the merge even when the parts do not make the whole image and every pass "
      "(else refused, exit 2); it keeps its film state, so it merges with the rest later");
  return cmd;
}

int merge_command(const MergeRequest& req) {
  check_outputs(req);
  for (const std::string& out : {req.exr, req.png}) {
    if (!out.empty()) prepare_output_folder(out);
  }
  std::vector<FilmPart> parts = read_parts(req.parts);
  const std::size_t count = parts.size();
  const FilmFile merged = merge_film_parts(std::move(parts));
  if (!req.partial) check_whole(merged, count);
  const imaging::ColorPipeline color(req.ocio_config);
  write_render(merged.header, *merged.film, {req.exr, req.png, &color, StopReason::None});
  const Window& box = merged.film->window();
  std::fprintf(stderr, "arbor: merged %zu part%s: %dx%d at (%d, %d), %s of %d%s\n", count,
               count == 1 ? "" : "s", box.width(), box.height(), box.x0, box.y0,
               passes_text(merged.film->pass_begin(), merged.film->next_pass()).c_str(),
               merged.header.plan.passes(),
               film_complete(merged.header, *merged.film) ? " (the whole render)" : "");
  std::fprintf(stderr, "arbor: wrote %s\n", req.exr.c_str());
  if (!req.png.empty()) std::fprintf(stderr, "arbor: wrote %s\n", req.png.c_str());
  return 0;
}

}  // namespace arbor::app
