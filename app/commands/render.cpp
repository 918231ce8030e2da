// `arbor render`: load the scene, apply the overrides, check the outputs, build, render in
// passes (stopping, checkpointing or resuming as asked), write.
#include "app/commands/render.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <vector>

#include <climits>
#include <filesystem>
#include <cstdlib>
#include <unistd.h>

#include "app/commands/fingerprint.h"
#include "app/commands/metering.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/executable.h"
#include "common/input_file.h"
#include "common/progress.h"
#include "common/rng.h"
#include "common/parse.h"
#include "common/strings.h"
#include "formats/scene_file.h"
#include "imaging/color.h"
#include "imaging/image_output.h"
#include "scene/frame.h"
#include "scene/render_budget.h"
#include "scene/render_input.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"
#include "tracer/exposure.h"
#include "tracer/film_file.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"
#include "tracer/render_output.h"

namespace arbor::app {

using tracer::EmbreeDevice;
using tracer::Film;
using tracer::FilmFile;
using tracer::FilmHeader;
using tracer::integrator_aov_names;
using tracer::kSkyMapWidth;
using tracer::name_of;
using tracer::number_text;
using tracer::pass_plan_for;
using tracer::PassPlan;
using tracer::read_film_state;
using tracer::render_path;
using tracer::render_treemaker;
using tracer::RenderJob;
using tracer::RenderOutcome;
using tracer::RenderWrite;
using tracer::settings_difference;
using tracer::Sky;
using tracer::state_path;
using tracer::StopReason;
using tracer::Window;
using tracer::World;
using tracer::write_render;

namespace {

// The weights for the EXR's arbor:treemaker_weights: one set when every tree shares it.
std::string treemaker_weights_text(const scene::Scene& scene) {
  std::string text;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const materials::TreemakerWeights& w = scene.instances[i].treemaker;
    char buf[160];
    std::snprintf(buf, sizeof buf, "ambient=%.9g lambert=%.9g height=%.9g radius=%.9g angle=%.9g",
                  w.ambient, w.lambert, w.height, w.radius, w.angle);
    if (i == 0)
      text = buf;
    else if (text != buf)
      return "per tree";
  }
  return text;
}

}  // namespace

namespace {

// An installed scene (<prefix>/share/arbor/scenes/) names its outputs relative to itself, in a
// folder users do not write in: those outputs go under the current folder instead, with a note.
void relocate_installed_outputs(spec::SceneDesc& scene, const RenderRequest& a) {
  char shared[PATH_MAX], folder[PATH_MAX];
  const std::size_t slash = scene.path.find_last_of('/');
  const std::string scene_folder =
      slash == std::string::npos ? "." : scene.path.substr(0, slash + 1);
  if (!::realpath(installed_data_path("").c_str(), shared) ||
      !::realpath(scene_folder.c_str(), folder))
    return;
  const std::string root = std::string(shared) + "/";
  if (std::string(folder).rfind(root, 0) != 0) return;
  const std::string prefix = slash == std::string::npos ? "" : scene_folder;
  for (std::string* out :
       {a.exr.empty() ? &scene.output.exr : nullptr, a.png.empty() ? &scene.output.png : nullptr}) {
    if (!out || out->empty() || prefix.empty() || out->rfind(prefix, 0) != 0) continue;
    // Its place under the installed data ("out/default.exr" for scenes/../out/default.exr) is
    // its place under the current folder; one outside the data keeps only its name.
    const std::filesystem::path inside =
        (std::filesystem::path(folder) / out->substr(prefix.size()))
            .lexically_normal()
            .lexically_relative(shared);
    const std::string here = inside.empty() || *inside.begin() == ".."
                                 ? std::filesystem::path(*out).filename().string()
                                 : inside.string();
    std::fprintf(
        stderr,
        "arbor: %s is an installed scene; its output %s goes under the current folder: %s\n",
        scene.path.c_str(), out->c_str(), here.c_str());
    *out = here;
  }
}

// The scene as this command renders it: loaded, its installed outputs moved under the current
// folder, the overrides, -o/--png, the frame and the checkpoint interval applied; InputError
// when it has nothing to write or an output of the wrong kind.
spec::SceneDesc prepared_scene(const RenderRequest& a) {
  spec::SceneDesc scene = formats::load_scene(a.scene);
  relocate_installed_outputs(scene, a);
  apply_overrides(scene, a.overrides);
  scene.render.threads = a.threads;
  // -o replaces the scene's outputs: its PNG too, which is then written only with --png.
  if (!a.exr.empty()) {
    scene.output.exr = a.exr;
    scene.output.png.clear();
  }
  if (!a.png.empty()) scene.output.png = a.png;
  scene::apply_frame(scene, a.frame);
  if (a.checkpoint_seconds) scene.output.checkpoint_seconds = *a.checkpoint_seconds;
  const std::string& exr = scene.output.exr;
  if (exr.empty() && scene.output.png.empty()) {
    throw InputError({a.scene, 0, 0},
                     "nothing to write: give -o OUT.exr, --png OUT.png or an [output] table");
  }
  if (!exr.empty() && !ends_with(exr, ".exr")) {
    throw InputError({}, "the EXR output must end in .exr: " + exr);
  }
  if (!scene.output.png.empty() && !ends_with(scene.output.png, ".png")) {
    throw InputError({}, "the PNG output must end in .png: " + scene.output.png);
  }
  return scene;
}

// The passes and the window this run renders (--passes, --crop), checked against the render.
struct RunRange {
  int pass_begin = 0, pass_end = 0;
  Window window;
};

RunRange run_range(const spec::SceneDesc& scene, const RenderRequest& a, const PassPlan& plan) {
  const spec::RenderSettings& r = scene.render;
  RunRange run{0, plan.passes(), {0, 0, r.width, r.height}};
  if (!a.passes.empty()) {
    const std::vector<int> v =
        parse_integers(a.passes, ':', 2, "--passes", "A:B (passes A to B-1)");
    if (v[0] >= v[1] || v[1] > plan.passes()) {
      throw InputError({}, "--passes " + a.passes + ": the render has passes 0 to " +
                               std::to_string(plan.passes()) + " (" + std::to_string(plan.spp) +
                               " spp in passes of " + std::to_string(plan.pass_spp) +
                               "), so A:B needs 0 <= A < B <= " + std::to_string(plan.passes()));
    }
    run.pass_begin = v[0];
    run.pass_end = v[1];
  }
  if (!a.crop.empty()) {
    const std::vector<int> v =
        parse_integers(a.crop, ',', 4, "--crop", "X0,Y0,X1,Y1 (pixels, end exclusive)");
    run.window = {v[0], v[1], v[2], v[3]};
    if (run.window.width() <= 0 || run.window.height() <= 0 || run.window.x1 > r.width ||
        run.window.y1 > r.height) {
      throw InputError({}, "--crop " + a.crop + " is not a window of the " +
                               std::to_string(r.width) + "x" + std::to_string(r.height) +
                               " image (X0 < X1 <= width, Y0 < Y1 <= height)");
    }
  }
  if (a.resume && scene.output.exr.empty()) {
    throw InputError({},
                     "--resume needs an EXR output (-o OUT.exr or the scene's output.exr): its "
                     "film state is kept beside it");
  }
  // A work unit is never written over the scene's own outputs: it names its part with -o.
  if ((!a.passes.empty() || !a.crop.empty()) && a.exr.empty()) {
    throw InputError(
        {}, std::string(!a.passes.empty() ? "--passes" : "--crop") +
                " renders a part of the image: name the part with -o PART.exr (the scene's own "
                "outputs are not overwritten by a part)");
  }
  if (run.pass_begin > 0 && r.noise_threshold > 0) {
    throw InputError({},
                     "--passes " + a.passes +
                         " starts after pass 0, but adaptive sampling "
                         "(render.noise_threshold) decides each pass from the passes before it; "
                         "split an adaptive render by --crop instead");
  }
  return run;
}

// InputError when an output would overwrite an input; then makes the outputs' missing folders.
void check_outputs(const spec::SceneDesc& scene) {
  const std::string& exr = scene.output.exr;
  const std::vector<std::string> inputs = spec::scene_inputs(scene);
  if (!exr.empty()) {
    refuse_overwriting("the EXR output", exr, inputs);
    refuse_overwriting("the EXR output's film state", state_path(exr), inputs, {exr});
  }
  if (!scene.output.png.empty()) {
    refuse_overwriting("the PNG output", scene.output.png, inputs,
                       {exr, exr.empty() ? "" : state_path(exr)});
  }
}

FilmHeader film_header(const spec::SceneDesc& scene, const scene::RenderInput& input,
                       const RenderRequest& a, const imaging::ColorPipeline& color,
                       const PassPlan& plan, const RunRange& run) {
  const spec::RenderSettings& r = scene.render;
  FilmHeader header;
  header.fingerprint =
      render_fingerprint(scene, a.overrides.time, a.frame, color.config_path(), header.settings);
  header.scene = scene.path;
  header.full_width = r.width;
  header.full_height = r.height;
  header.plan = plan;
  header.pass_end = run.pass_end;
  header.noise_threshold = r.noise_threshold;
  header.min_spp = r.min_spp;
  header.integrator = input.render.integrator;
  header.regularize = input.render.regularize;
  header.lod_quality = scene.render.lod ? scene.render.lod_quality : 0.0;
  header.seed = r.seed;
  header.output = scene.output;
  return header;
}

// The film this run continues (--resume: the state beside the EXR, its totals copied into
// `header`) or a new one; nullptr when a resume finds nothing left to do.
std::unique_ptr<Film> open_film(const spec::SceneDesc& scene, const scene::RenderInput& input,
                                const RenderRequest& a, const RunRange& run, FilmHeader& header) {
  if (!a.resume) {
    return std::make_unique<Film>(run.window, integrator_aov_names(input).size(), run.pass_begin,
                                  run.pass_begin > 0, scene.output.wants_ids());
  }
  const std::string& exr = scene.output.exr;
  const std::string state = state_path(exr);
  if (::access(state.c_str(), F_OK) != 0) {
    if (imaging::finished_exr_fingerprint(exr) == header.fingerprint) {
      std::fprintf(stderr, "arbor: %s is already finished; nothing to resume\n", exr.c_str());
      return nullptr;
    }
    throw InputError({state, 0, 0},
                     "--resume: there is no film state beside " + exr +
                         " (it is written when a render stops early, at checkpoints and "
                         "for --passes/--crop parts)");
  }
  FilmFile saved = read_film_state(state);
  if (saved.header.fingerprint != header.fingerprint) {
    throw InputError({state, 0, 0}, "--resume: it was rendered from " + saved.header.scene +
                                        " with other settings or inputs (" +
                                        settings_difference(saved.header.settings, header.settings,
                                                            "in the state", "in this command") +
                                        "); give the same scene, files and options");
  }
  if (saved.film->window() != run.window || saved.film->pass_begin() != run.pass_begin ||
      saved.header.pass_end != run.pass_end) {
    throw InputError({state, 0, 0},
                     "--resume: it holds another --crop or --passes than this command asks for");
  }
  header.seconds = saved.header.seconds;
  header.nonfinite = saved.header.nonfinite;
  header.rays = saved.header.rays;
  if (saved.film->next_pass() == run.pass_end) {
    std::fprintf(stderr, "arbor: %s already holds passes %d to %d; nothing to resume\n",
                 exr.c_str(), run.pass_begin, run.pass_end - 1);
    return nullptr;
  }
  return std::move(saved.film);
}

// What the render did, for the report.
struct RunResult {
  imaging::RenderStats stats;
  RenderOutcome outcome;
  int first_pass = 0;
  std::size_t instances = 0, prototypes = 0;
  double build_seconds = 0;
  std::size_t blades = 0, distinct_blades = 0, tiles = 0, meadow_bytes = 0;  // the meadow's
};

// Builds the scene and renders the film's remaining passes, writing checkpoints and, at the end,
// the outputs (unless no pass finished).
RunResult build_and_render(const spec::SceneDesc& scene, const scene::RenderInput& input,
                           const RenderRequest& a, const imaging::ColorPipeline& color,
                           const PassPlan& plan, const RunRange& run, FilmHeader& header,
                           Film& film) {
  const spec::RenderSettings& r = scene.render;
  const bool treemaker = input.render.integrator == spec::Integrator::Treemaker;
  const std::uint64_t unit_passes =
      run.pass_begin > 0 ? static_cast<std::uint64_t>(run.pass_end - run.pass_begin) : 0;
  const EmbreeDevice device(r.threads > 0 ? "threads=" + std::to_string(r.threads) : "");
  const Sky sky(input.sky, input.sun, color.xyz_to_scene_linear(), kSkyMapWidth,
                input.render.aerial_perspective);
  const MeterBuild meter{&device, color.config_path(),
                         scene::geometry_budget(scene, Film::costs(), a.force,
                                                scene::usable_memory_bytes(), unit_passes),
                         static_cast<unsigned>(std::max(0, r.threads))};
  // A later frame meters frame 0 first (its world gone before this frame's is built).
  const double frame_zero =
      meters_frame_zero(scene, input) ? frame_zero_exposure(scene, input, sky, meter) : 0.0;
  Progress build_progress("build", 1);
  const std::unique_ptr<const scene::Scene> built = scene::build_scene(
      scene, color.config_path(), &build_progress, meter.geometry_budget, meter.threads);
  const World world(*built, device);
  build_progress.finish();
  if (treemaker) header.treemaker_weights = treemaker_weights_text(*built);
  header.object_names = built->object_names;
  header.material_names = built->material_names;
  // [camera] exposure = "auto": metered once per scene, the same for every unit, resume, frame,
  // integrator and --transparent (tracer/exposure.h).
  const scene::RenderInput metered = with_scene_exposure(scene, input, world, sky, frame_zero);
  // Every digit: `exposure = <it>` renders the same pixels.
  header.exposure =
      number_text(metered.camera.exposure) + (input.camera.auto_exposure ? " (metered)" : "");

  RunResult result;
  result.instances = built->stats.instances;
  result.prototypes = built->stats.prototypes;
  result.build_seconds = built->stats.build_seconds + world.build_seconds();
  result.blades = built->meadow.placed_blades();
  result.distinct_blades = built->meadow.distinct_blades();
  result.tiles = built->meadow.tiles.size();
  result.meadow_bytes = built->meadow.bytes();
  RenderWrite write{scene.output.exr, scene.output.png, &color, StopReason::None,
                    !a.passes.empty() || !a.crop.empty()};
  RenderJob job;
  job.plan = plan;
  job.pass_end = run.pass_end;
  job.adaptive = {r.noise_threshold, r.min_spp};
  job.time_limit = a.time_limit;
  job.checkpoint_seconds = scene.output.checkpoint_seconds;
  job.stop = &stop_signal();
  const double seconds_before = header.seconds;
  job.checkpoint = [&](const Film& f) {
    FilmHeader h = header;
    h.seconds = seconds_before + result.stats.seconds;
    RenderWrite w = write;
    w.stopped = StopReason::InProgress;
    write_render(h, f, w);
  };
  result.first_pass = film.next_pass();
  Progress progress("render", 1);
  stop_gracefully_on_signal(true);
  const imaging::ColorTransform to_output = color.to_output(scene.output.colorspace);
  result.outcome =
      treemaker
          ? render_treemaker(metered, world, sky, to_output, job, film, &progress, result.stats)
          : render_path(metered, world, sky, to_output, job, film, &progress, result.stats);
  progress.finish();
  header.seconds = seconds_before + result.stats.seconds;
  header.nonfinite += result.stats.nonfinite;
  header.rays += result.stats.rays;
  write.stopped = result.outcome.stopped;
  if (film.next_pass() == result.first_pass) {
    // Stopped before one pass finished: the old outputs stay as they were.
    std::fprintf(stderr, "arbor: stopped before a pass finished; nothing written\n");
  } else {
    write_render(header, film, write);
  }
  stop_gracefully_on_signal(false);
  return result;
}

void report(const spec::SceneDesc& scene, const PassPlan& plan, const RunRange& run,
            const Film& film, const RunResult& result) {
  const imaging::RenderStats& stats = result.stats;
  const Window& window = run.window;
  const double seconds = std::max(stats.seconds, 1e-9);
  const int done = plan.samples(run.pass_begin, film.next_pass());
  // With adaptive sampling pixels stop early: the mean is what was rendered, `done` the most.
  char spp_text[80];
  if (scene.render.noise_threshold > 0.0) {
    double total = 0.0;
    for (std::size_t p = 0; p < window.pixels(); ++p) total += film.state(p).count;
    std::snprintf(spp_text, sizeof spp_text, "a mean of %.1f spp (at most %d)",
                  total / double(window.pixels()), done);
  } else {
    std::snprintf(spp_text, sizeof spp_text, "%d spp", done);
  }
  std::fprintf(
      stderr,
      "arbor: rendered %dx%d at %s (passes %d to %d of %d) in %.2f s (%.3g samples/s, %.3g rays/s; "
      "%zu trees from %zu prototypes, built in %.2f s)\n",
      window.width(), window.height(), spp_text, run.pass_begin, film.next_pass() - 1,
      plan.passes(), stats.seconds, double(stats.samples) / seconds, double(stats.rays) / seconds,
      result.instances, result.prototypes, result.build_seconds);
  if (result.blades > 0) {
    std::fprintf(stderr,
                 "arbor: a meadow of %zu grass blades (%zu distinct, in %zu tiles: %.1f MB)\n",
                 result.blades, result.distinct_blades, result.tiles,
                 static_cast<double>(result.meadow_bytes) / 1e6);
  }
  if (result.outcome.stopped != StopReason::None) {
    std::fprintf(stderr,
                 "arbor: stopped early (%s) after %d of %d passes; continue with --resume\n",
                 name_of(result.outcome.stopped), film.next_pass() - run.pass_begin,
                 run.pass_end - run.pass_begin);
  }
  if (stats.nonfinite > 0) {
    std::fprintf(stderr, "arbor: warning: %llu samples were NaN or infinite and were left out\n",
                 static_cast<unsigned long long>(stats.nonfinite));
  }
  if (film.next_pass() != result.first_pass) {
    for (const std::string& out : {scene.output.exr, scene.output.png}) {
      if (!out.empty()) std::fprintf(stderr, "arbor: wrote %s\n", out.c_str());
    }
  }
}

}  // namespace

CLI::App* add_render_command(CLI::App& app, RenderRequest& render) {
  CLI::App* cmd = app.add_subcommand(
      "render", "Render a scene file to EXR/PNG (path tracer, or TREE-MAKER's shading)");
  cmd->add_option("SCENE", render.scene, "scene file (.toml)")->required();
  cmd->add_option("-o,--output", render.exr,
                  "EXR to write: replaces the scene's [output] exr and png (a PNG is then written "
                  "only with --png)");
  cmd->add_option("--png", render.png, "PNG to write through the display view");
  add_override_options(
      cmd, render.overrides,
      kSppOption | kSeedOption | kIntegratorOption | kTransparentOption | kRegularizeOption,
      "samples per pixel of the integrator in use (overrides render.spp, or "
      "render.treemaker_spp for treemaker)");
  cmd->add_option("--threads", render.threads, "threads (0: all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--frame", render.frame,
                  "render frame N of the scene's [animation]: every tree at time N / fps, the "
                  "frame's own seed (unless animation.pin_seed), N in place of #### in the outputs")
      ->check(CLI::Range(0, 1000000));
  cmd->add_flag("--force", render.force,
                "render even when the image and trees are estimated to need more memory "
                "than this machine (or ulimit) allows");
  cmd->add_flag("--resume", render.resume,
                "continue the render from the film state beside its EXR (OUT.exr.state), to the "
                "image an uninterrupted render gives");
  cmd->add_option(
         "--time-limit", render.time_limit,
         "seconds: stop after the last pass that fits (at least one pass is rendered; 0: no limit)")
      ->check(finite_in(0.0, 1e9));
  cmd->add_option(
         "--checkpoint-seconds", render.checkpoint_seconds,
         "rewrite the outputs this often as passes finish (overrides output.checkpoint_seconds)")
      ->check(finite_in(0.0, 1e7));
  cmd->add_option("--passes", render.passes,
                  "A:B: render only passes A to B-1 (a work unit for arbor merge; needs -o)")
      ->check(non_empty());
  cmd->add_option(
         "--crop", render.crop,
         "X0,Y0,X1,Y1: render only that window (pixels, end exclusive), each pixel as in the "
         "whole image (needs -o)")
      ->check(non_empty());
  cmd->footer(
      "Exposure: [camera] exposure = \"auto\" is metered once per scene (the path tracer's view of "
      "the scene at its animation's frame 0, the sky included), so --transparent, --integrator "
      "treemaker, --regularize, every --frame, every --passes/--crop unit and --resume render at "
      "the same exposure; the EXR's arbor:exposure records it (give that number as exposure to "
      "fix it).");
  return cmd;
}

int render_command(const RenderRequest& a) {
  const spec::SceneDesc scene = prepared_scene(a);
  const scene::RenderInput input = scene::render_input(scene);
  if (input.render.integrator != spec::Integrator::Treemaker &&
      input.output.aovs.has(imaging::Aov::Treemaker)) {
    throw InputError(scene.output.treemaker_aov_where,
                     "output.aovs lists \"treemaker\", which only the treemaker integrator writes "
                     "(render it with --integrator treemaker)");
  }
  const PassPlan plan = pass_plan_for(input.render);
  const RunRange run = run_range(scene, a, plan);
  check_outputs(scene);
  const imaging::ColorPipeline color(a.ocio_config);
  color.check(scene.output, scene.output.where);
  // Last of the checks (nothing is left behind when an earlier one fails): make missing folders.
  for (const std::string& out : {scene.output.exr, scene.output.png}) {
    if (!out.empty()) prepare_output_folder(out);
  }
  FilmHeader header = film_header(scene, input, a, color, plan, run);
  scene::check_render_memory(
      scene, Film::costs(), a.force, scene::usable_memory_bytes(),
      run.pass_begin > 0 ? static_cast<std::uint64_t>(run.pass_end - run.pass_begin) : 0);
  const std::unique_ptr<Film> film = open_film(scene, input, a, run, header);
  if (!film) return 0;
  const RunResult result = build_and_render(scene, input, a, color, plan, run, header, *film);
  report(scene, plan, run, *film, result);
  const int signal = stop_signal().load();
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace arbor::app
