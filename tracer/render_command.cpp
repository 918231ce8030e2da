// `arbor render`: load the scene, apply the overrides, check the outputs, build, render in
// passes (stopping, checkpointing or resuming as asked), write.
#include "tracer/render_command.h"

#include <algorithm>
#include <charconv>
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

#include <OpenImageIO/imageio.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/executable.h"
#include "common/input_file.h"
#include "common/progress.h"
#include "common/rng.h"
#include "common/strings.h"
#include "formats/scene_desc.h"
#include "imaging/color.h"
#include "scene/render_budget.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"
#include "tracer/film_file.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"
#include "tracer/render_output.h"

namespace arbor::trace {

namespace {

// The weights for the EXR's arbor:treemaker_weights: one set when every tree shares it.
std::string treemaker_weights_text(const Scene& scene) {
  std::string text;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const mat::TreemakerWeights& w = scene.instances[i].treemaker;
    char buf[160];
    std::snprintf(buf, sizeof buf, "ambient=%.9g lambert=%.9g height=%.9g radius=%.9g angle=%.9g",
                  w.ambient, w.lambert, w.height, w.radius, w.angle);
    if (i == 0) text = buf;
    else if (text != buf) return "per tree";
  }
  return text;
}

}  // namespace

std::vector<int> parse_integers(const std::string& text, char sep, std::size_t count, const char* option,
                                const char* form) {
  std::vector<int> v;
  const char* p = text.data();
  const char* end = text.data() + text.size();
  while (v.size() < count) {
    int x = 0;
    const auto [next, ec] = std::from_chars(p, end, x);
    if (ec != std::errc() || x < 0) break;
    v.push_back(x);
    p = next;
    if (v.size() < count) {
      if (p == end || *p != sep) break;
      ++p;
    }
  }
  if (v.size() != count || p != end) {
    throw InputError({}, std::string(option) + " '" + text + "' is not of the form " + form);
  }
  return v;
}

namespace {

// The hash of everything that decides the pixels: the settings (not the threads, the outputs or
// the pass range and window of a work unit), the bytes of the scene and each of its inputs, and
// the OCIO config.
// Also sets `settings` to the same, readable: "name value" items joined by "; ", so that a
// refused resume or merge can say which differ (settings_difference).
std::string render_fingerprint(const SceneDesc& scene, const RenderRequest& a, const std::string& ocio,
                               std::string& settings) {
  const RenderSettings& r = scene.render;
  std::ostringstream s;
  s.precision(17);
  s << "size " << r.width << "x" << r.height << "; spp " << r.spp << "; pass_spp " << r.pass_spp
    << "; independent_passes " << (r.independent_passes ? "true" : "false") << "; seed " << r.seed
    << "; integrator " << r.integrator << "; max_depth " << r.max_depth << "; treemaker_spp " << r.treemaker_spp
    << "; noise_threshold " << r.noise_threshold << "; min_spp " << r.min_spp << "; transparent_sky "
    << (scene.output.transparent_sky ? "true" : "false") << "; ids " << (scene.output.wants_ids() ? "kept" : "none")
    << "; --time " << (a.time ? std::to_string(*a.time) : std::string("none"));
  if (a.frame) s << "; frame " << *a.frame << "; clock " << scene.clock;
  std::vector<std::string> files = scene_inputs(scene);
  files.push_back(ocio);
  // The inputs by their place in the scene and their bytes, not by how their paths are spelt
  // (scene.toml and ./scene.toml are one render; the scene's own text names its inputs).
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string role = i == 0 ? "the scene file" : i + 1 == files.size() ? "the OCIO config" : "input " + file_name(files[i]);
    s << "; " << role << " " << fingerprint_hex(input_digest(files[i], role));
  }
  settings = s.str();
  return fingerprint_hex(fnv1a("arbor render 2 " + settings));
}

// The EXR's arbor:fingerprint and whether it says it is a finished render, or "" when it cannot
// be read.
std::string finished_fingerprint(const std::string& exr) {
  auto in = OIIO::ImageInput::open(exr);
  if (!in) return "";
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.get_int_attribute("arbor:incomplete", 0) != 0) return "";
  return spec.get_string_attribute("arbor:fingerprint");
}

}  // namespace

void apply_frame(SceneDesc& scene, std::optional<int> frame) {
  const bool numbered = scene.output.exr.find('#') != std::string::npos || scene.output.png.find('#') != std::string::npos;
  if (!frame) {
    if (numbered) {
      throw InputError({}, "the output " + (scene.output.exr.find('#') != std::string::npos ? scene.output.exr : scene.output.png) +
                               " names a frame number (#): give --frame N");
    }
    return;
  }
  const AnimationDesc& an = scene.animation;
  if (an.frames == 0) {
    throw InputError({scene.path, 0, 0}, "--frame " + std::to_string(*frame) + ": the scene has no [animation] table");
  }
  if (*frame < 0 || *frame >= an.frames) {
    throw InputError(an.where, "--frame " + std::to_string(*frame) + " is outside the animation's frames 0 to " +
                                   std::to_string(an.frames - 1));
  }
  scene.clock = *frame / an.fps;
  if (!an.pin_seed) scene.render.seed = derive_key(scene.render.seed, static_cast<std::uint64_t>(*frame));
  scene.output.exr = frame_path(scene.output.exr, *frame);
  scene.output.png = frame_path(scene.output.png, *frame);
}

namespace {

// An installed scene (<prefix>/share/arbor/scenes/) names its outputs relative to itself, in a
// folder users do not write in: those outputs go under the current folder instead, with a note.
void relocate_installed_outputs(SceneDesc& scene, const RenderRequest& a) {
  char shared[PATH_MAX], folder[PATH_MAX];
  const std::size_t slash = scene.path.find_last_of('/');
  const std::string scene_folder = slash == std::string::npos ? "." : scene.path.substr(0, slash + 1);
  if (!::realpath(installed_data_path("").c_str(), shared) || !::realpath(scene_folder.c_str(), folder)) return;
  const std::string root = std::string(shared) + "/";
  if (std::string(folder).rfind(root, 0) != 0) return;
  const std::string prefix = slash == std::string::npos ? "" : scene_folder;
  for (std::string* out : {a.exr.empty() ? &scene.output.exr : nullptr, a.png.empty() ? &scene.output.png : nullptr}) {
    if (!out || out->empty() || prefix.empty() || out->rfind(prefix, 0) != 0) continue;
    // Its place under the installed data ("out/default.exr" for scenes/../out/default.exr) is
    // its place under the current folder; one outside the data keeps only its name.
    const std::filesystem::path inside =
        (std::filesystem::path(folder) / out->substr(prefix.size())).lexically_normal().lexically_relative(shared);
    const std::string here = inside.empty() || *inside.begin() == ".." ? std::filesystem::path(*out).filename().string()
                                                                         : inside.string();
    std::fprintf(stderr, "arbor: %s is an installed scene; its output %s goes under the current folder: %s\n",
                 scene.path.c_str(), out->c_str(), here.c_str());
    *out = here;
  }
}

}  // namespace

int render_command(const RenderRequest& a) {
  SceneDesc scene = load_scene(a.scene);
  relocate_installed_outputs(scene, a);
  RenderSettings& r = scene.render;
  if (!a.integrator.empty()) r.integrator = a.integrator;
  // --spp sets the sample count of the integrator in use (the scene keeps one for each).
  const bool treemaker = r.integrator == "treemaker";
  if (a.spp > 0) (treemaker ? r.treemaker_spp : r.spp) = a.spp;
  if (a.width > 0) r.width = a.width;
  if (a.height > 0) r.height = a.height;
  if (a.seed) r.seed = *a.seed;
  r.threads = a.threads;
  if (a.time) {
    for (TreeDesc& t : scene.trees) t.time = *a.time;
  }
  // -o replaces the scene's outputs: its PNG too, which is then written only with --png.
  if (!a.exr.empty()) {
    scene.output.exr = a.exr;
    scene.output.png.clear();
  }
  if (!a.png.empty()) scene.output.png = a.png;
  apply_frame(scene, a.frame);
  if (a.checkpoint_seconds) scene.output.checkpoint_seconds = *a.checkpoint_seconds;
  if (a.transparent) scene.output.transparent_sky = true;
  if (!treemaker &&
      std::find(scene.output.aovs.begin(), scene.output.aovs.end(), "treemaker") != scene.output.aovs.end()) {
    throw InputError(scene.output.treemaker_aov_where,
                     "output.aovs lists \"treemaker\", which only the treemaker integrator writes "
                     "(render it with --integrator treemaker)");
  }
  const std::string& exr = scene.output.exr;
  if (exr.empty() && scene.output.png.empty()) {
    throw InputError({a.scene, 0, 0}, "nothing to write: give -o OUT.exr, --png OUT.png or an [output] table");
  }
  if (!exr.empty() && !ends_with(exr, ".exr")) {
    throw InputError({}, "the EXR output must end in .exr: " + exr);
  }
  if (!scene.output.png.empty() && !ends_with(scene.output.png, ".png")) {
    throw InputError({}, "the PNG output must end in .png: " + scene.output.png);
  }

  // The passes and the window of this run.
  const PassPlan plan{treemaker ? r.treemaker_spp : r.spp, r.pass_spp, r.independent_passes};
  int pass_begin = 0, pass_end = plan.passes();
  if (!a.passes.empty()) {
    const std::vector<int> v = parse_integers(a.passes, ':', 2, "--passes", "A:B (passes A to B-1)");
    if (v[0] >= v[1] || v[1] > plan.passes()) {
      throw InputError({}, "--passes " + a.passes + ": the render has passes 0 to " + std::to_string(plan.passes()) +
                               " (" + std::to_string(plan.spp) + " spp in passes of " + std::to_string(plan.pass_spp) +
                               "), so A:B needs 0 <= A < B <= " + std::to_string(plan.passes()));
    }
    pass_begin = v[0];
    pass_end = v[1];
  }
  Window window{0, 0, r.width, r.height};
  if (!a.crop.empty()) {
    const std::vector<int> v = parse_integers(a.crop, ',', 4, "--crop", "X0,Y0,X1,Y1 (pixels, end exclusive)");
    window = {v[0], v[1], v[2], v[3]};
    if (window.width() <= 0 || window.height() <= 0 || window.x1 > r.width || window.y1 > r.height) {
      throw InputError({}, "--crop " + a.crop + " is not a window of the " + std::to_string(r.width) + "x" +
                               std::to_string(r.height) + " image (X0 < X1 <= width, Y0 < Y1 <= height)");
    }
  }
  if (a.resume && exr.empty()) {
    throw InputError({}, "--resume needs an EXR output (-o OUT.exr or the scene's output.exr): its film state is kept beside it");
  }
  // A work unit is never written over the scene's own outputs: it names its part with -o.
  if ((!a.passes.empty() || !a.crop.empty()) && a.exr.empty()) {
    throw InputError({}, std::string(!a.passes.empty() ? "--passes" : "--crop") +
                             " renders a part of the image: name the part with -o PART.exr (the scene's own "
                             "outputs are not overwritten by a part)");
  }
  if (pass_begin > 0 && r.noise_threshold > 0) {
    throw InputError({}, "--passes " + a.passes + " starts after pass 0, but adaptive sampling "
                         "(render.noise_threshold) decides each pass from the passes before it; "
                         "split an adaptive render by --crop instead");
  }

  const std::vector<std::string> inputs = scene_inputs(scene);
  if (!exr.empty()) {
    refuse_overwriting("the EXR output", exr, inputs);
    refuse_overwriting("the EXR output's film state", state_path(exr), inputs, {exr});
  }
  if (!scene.output.png.empty()) {
    refuse_overwriting("the PNG output", scene.output.png, inputs, {exr, exr.empty() ? "" : state_path(exr)});
  }
  const ColorPipeline color(a.ocio_config);
  color.check(scene.output);
  // Last of the checks (nothing is left behind when an earlier one fails): make missing folders.
  for (const std::string& out : {exr, scene.output.png}) {
    if (!out.empty()) prepare_output_folder(out);
  }
  const std::vector<std::string> extra_names = integrator_aov_names(scene);

  FilmHeader header;
  header.fingerprint = render_fingerprint(scene, a, color.config_path(), header.settings);
  header.scene = scene.path;
  header.full_width = r.width;
  header.full_height = r.height;
  header.plan = plan;
  header.pass_end = pass_end;
  header.noise_threshold = r.noise_threshold;
  header.min_spp = r.min_spp;
  header.integrator = r.integrator;
  header.seed = r.seed;
  header.colorspace = scene.output.colorspace;
  header.display = scene.output.display;
  header.view = scene.output.view;
  header.pixel_type = scene.output.pixel_type;
  header.aovs = scene.output.aovs;
  header.transparent_sky = scene.output.transparent_sky;

  check_render_memory(scene, a.force, usable_memory_bytes(),
                      pass_begin > 0 ? static_cast<std::uint64_t>(pass_end - pass_begin) : 0);
  std::unique_ptr<Film> film;
  if (a.resume) {
    const std::string state = state_path(exr);
    if (::access(state.c_str(), F_OK) != 0) {
      if (finished_fingerprint(exr) == header.fingerprint) {
        std::fprintf(stderr, "arbor: %s is already finished; nothing to resume\n", exr.c_str());
        return 0;
      }
      throw InputError({state, 0, 0}, "--resume: there is no film state beside " + exr +
                                          " (it is written when a render stops early, at checkpoints and "
                                          "for --passes/--crop parts)");
    }
    FilmFile saved = read_film_state(state);
    if (saved.header.fingerprint != header.fingerprint) {
      throw InputError({state, 0, 0}, "--resume: it was rendered from " + saved.header.scene +
                                          " with other settings or inputs (" +
                                          settings_difference(saved.header.settings, header.settings, "in the state", "in this command") +
                                          "); give the same scene, files and options");
    }
    if (saved.film->window() != window || saved.film->pass_begin() != pass_begin || saved.header.pass_end != pass_end) {
      throw InputError({state, 0, 0}, "--resume: it holds another --crop or --passes than this command asks for");
    }
    film = std::move(saved.film);
    header.seconds = saved.header.seconds;
    header.nonfinite = saved.header.nonfinite;
    header.rays = saved.header.rays;
    if (film->next_pass() == pass_end) {
      std::fprintf(stderr, "arbor: %s already holds passes %d to %d; nothing to resume\n", exr.c_str(),
                   pass_begin, pass_end - 1);
      return 0;
    }
  } else {
    film = std::make_unique<Film>(window, extra_names.size(), pass_begin, pass_begin > 0, scene.output.wants_ids());
  }

  const EmbreeDevice device(r.threads > 0 ? "threads=" + std::to_string(r.threads) : "");
  Progress build_progress("build", 1);
  const std::unique_ptr<const Scene> built =
      build_scene(scene, color.config_path(), &build_progress,
                  geometry_budget(scene, a.force, usable_memory_bytes(),
                                  pass_begin > 0 ? static_cast<std::uint64_t>(pass_end - pass_begin) : 0));
  const World world(*built, device);
  build_progress.finish();
  if (treemaker) header.treemaker_weights = treemaker_weights_text(*built);
  header.object_names = built->object_names;
  header.material_names = built->material_names;
  const Sky sky(scene.sky, scene.sun, color.xyz_to_scene_linear());

  RenderWrite write{exr, scene.output.png, &color, ""};
  RenderStats stats;
  RenderJob job;
  job.plan = plan;
  job.pass_end = pass_end;
  job.adaptive = {r.noise_threshold, r.min_spp};
  job.time_limit = a.time_limit;
  job.checkpoint_seconds = scene.output.checkpoint_seconds;
  job.stop = &stop_signal();
  const double seconds_before = header.seconds;
  job.checkpoint = [&](const Film& f) {
    FilmHeader h = header;
    h.seconds = seconds_before + stats.seconds;
    RenderWrite w = write;
    w.stopped = "in progress";
    write_render(h, f, w);
  };
  const int first_pass = film->next_pass();
  Progress progress("render", 1);
  stop_gracefully_on_signal(true);
  const ColorTransform to_output = color.to_output(scene.output.colorspace);
  const RenderOutcome outcome = treemaker ? render_treemaker(scene, world, sky, to_output, job, *film, &progress, stats)
                                          : render_path(scene, world, sky, to_output, job, *film, &progress, stats);
  progress.finish();
  const int signal = stop_signal().load();
  header.seconds = seconds_before + stats.seconds;
  header.nonfinite += stats.nonfinite;
  header.rays += stats.rays;
  write.stopped = outcome.stopped;
  if (film->next_pass() == first_pass) {
    // Stopped before one pass finished: the old outputs stay as they were.
    std::fprintf(stderr, "arbor: stopped before a pass finished; nothing written\n");
  } else {
    write_render(header, *film, write);
  }
  stop_gracefully_on_signal(false);
  const double seconds = std::max(stats.seconds, 1e-9);
  const int done = plan.samples(pass_begin, film->next_pass());
  // With adaptive sampling pixels stop early: the mean is what was rendered, `done` the most.
  char spp_text[80];
  if (r.noise_threshold > 0.0) {
    double total = 0.0;
    for (std::size_t p = 0; p < window.pixels(); ++p) total += film->state(p).count;
    std::snprintf(spp_text, sizeof spp_text, "a mean of %.1f spp (at most %d)", total / double(window.pixels()), done);
  } else {
    std::snprintf(spp_text, sizeof spp_text, "%d spp", done);
  }
  std::fprintf(stderr,
               "arbor: rendered %dx%d at %s (passes %d to %d of %d) in %.2f s (%.3g samples/s, %.3g rays/s; "
               "%zu trees from %zu prototypes, built in %.2f s)\n",
               window.width(), window.height(), spp_text, pass_begin, film->next_pass() - 1, plan.passes(),
               stats.seconds, double(stats.samples) / seconds, double(stats.rays) / seconds,
               built->stats.instances, built->stats.prototypes, built->stats.build_seconds + world.build_seconds());
  if (!outcome.stopped.empty()) {
    std::fprintf(stderr, "arbor: stopped early (%s) after %d of %d passes; continue with --resume\n",
                 outcome.stopped.c_str(), film->next_pass() - pass_begin, pass_end - pass_begin);
  }
  if (stats.nonfinite > 0) {
    std::fprintf(stderr, "arbor: warning: %llu samples were NaN or infinite and were left out\n",
                 static_cast<unsigned long long>(stats.nonfinite));
  }
  if (film->next_pass() != first_pass) {
    for (const std::string& out : {exr, scene.output.png}) {
      if (!out.empty()) std::fprintf(stderr, "arbor: wrote %s\n", out.c_str());
    }
  }
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace arbor::trace
