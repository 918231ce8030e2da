// The arbor command line: parses arguments, calls the libraries, maps errors to exit codes
// (0 success, 1 the work failed, 2 bad input or usage).
#include <algorithm>
#include <charconv>
#include <optional>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <new>

#include <OpenImageIO/imageio.h>
#include <string>

#include <CLI/CLI.hpp>

#include "arbor/version.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json.h"
#include "common/progress.h"
#include "generator/export/export_pbrt.h"
#include "formats/skeleton_file.h"
#include "generator/species.h"
#include "generator/geometry/tree_geometry.h"
#include "generator/geometry/tree_mesh.h"
#include "generator/export/tree_stats.h"
#include "generator/grow.h"
#include "imaging/compare.h"
#include "tracer/embree/embree_device.h"
#include "tracer/film.h"
#include "imaging/image_output.h"
#include "tracer/integrators/treemaker.h"
#include "scene/render_budget.h"
#include "formats/scene_desc.h"
#include "tracer/lights/sky.h"
#include "imaging/treemaker_fit.h"
#include "scene/scene.h"
#include "tracer/embree/world.h"
#include "formats/species_file.h"
#include "generator/export/export_mesh.h"
#include "generator/export/skeleton_file.h"

namespace {

// CLI11 check of a seed: a whole number from 0 to 2^64-1 (a larger one was once clamped
// silently, so different seeds gave the same tree).
CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& v) {
        std::uint64_t parsed = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), parsed);
        if (v.empty() || ec != std::errc() || end != v.data() + v.size()) {
          return "the seed must be a whole number from 0 to 2^64-1 (18446744073709551615), not '" + v + "'";
        }
        return std::string();
      },
      "UINT64");
}

// CLI11 check of a real number: finite and in [lo, hi], as strictly as the scene keys are
// checked (CLI11's Range lets NaN through).
CLI::Validator finite_in(double lo, double hi) {
  char range[64];
  std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
  return CLI::Validator(
      [lo, hi, text = std::string(range)](std::string& v) {
        double parsed = 0.0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), parsed);
        if (v.empty() || ec != std::errc() || end != v.data() + v.size() || !std::isfinite(parsed)) {
          return "'" + v + "' is not a finite number";
        }
        if (parsed < lo || parsed > hi) return v + " is out of range " + text;
        return std::string();
      },
      std::string("FLOAT in ") + range);
}

struct GrowArgs {
  std::string species;
  unsigned long long seed = 1;
  double time = 0.0;
  double quality = 1.0;
  std::string out;
  bool stats = false;
  bool json = false;
  bool force = false;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// InputError when writing `out` would replace one of `inputs` or an earlier output (the same
// file after symlinks, not merely the same spelling).
void refuse_overwriting(const std::string& what, const std::string& out,
                        const std::vector<std::string>& inputs, const std::vector<std::string>& outputs = {}) {
  for (const std::string& in : inputs) {
    if (arbor::same_file(out, in)) {
      throw arbor::InputError({}, what + " " + out + " would overwrite the input " + in);
    }
  }
  for (const std::string& other : outputs) {
    if (arbor::same_file(out, other)) {
      throw arbor::InputError({}, what + " " + out + " is also written as " + other);
    }
  }
}

int run_grow(const GrowArgs& a) {
  using namespace arbor;
  if (!a.out.empty() && !ends_with(a.out, ".obj") && !ends_with(a.out, ".ply") &&
      !ends_with(a.out, ".pbrt") && !ends_with(a.out, ".skel")) {
    throw InputError({}, "-o " + a.out + ": the output must be .obj, .ply, .pbrt or .skel");
  }
  if (!a.out.empty()) {
    refuse_overwriting("-o", a.out, {a.species});
    check_output_folder(a.out);
  }
  gen::Species species = gen::load_species(a.species);
  for (const std::string& w : species.warnings) std::fprintf(stderr, "%s\n", w.c_str());

  Progress progress("grow", 1);
  gen::GrowOptions options;
  options.seed = a.seed;
  options.time = a.time;
  options.quality = a.quality;
  options.force = a.force;
  options.progress = &progress;
  const auto start = std::chrono::steady_clock::now();
  gen::Skeleton skeleton;
  try {
    skeleton = gen::grow_tree(species, options);
  } catch (const RuntimeFailure& e) {
    // Refusing an absurd size is about the input: report it against the species file.
    throw InputError({a.species, 0, 0}, e.what());
  }
  progress.finish();
  gen::TreeStats stats = gen::compute_stats(skeleton);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  long long mesh_triangles = -1;
  if (!a.out.empty() || a.stats || a.json) {
    const auto geometry_start = std::chrono::steady_clock::now();
    const gen::TreeGeometry geometry =
        gen::build_tree_geometry(skeleton, gen::geometry_options_for(species.leaf));
    gen::add_geometry_stats(
        stats, geometry.stats,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - geometry_start).count());
    if (ends_with(a.out, ".skel")) {
      gen::write_skeleton_file(skeleton, a.out);
    } else if (ends_with(a.out, ".pbrt")) {
      gen::write_pbrt(geometry, species.bark, species.leaf, a.out);
    } else if (!a.out.empty()) {
      const gen::TreeMesh mesh = gen::tessellate(geometry);
      mesh_triangles = static_cast<long long>(mesh.triangle_count());
      if (ends_with(a.out, ".obj")) gen::write_obj(mesh, a.out);
      else gen::write_ply(mesh, a.out);
    }
  }
  if (a.json) {
    std::fputs(gen::stats_json(stats, species.name, a.seed, mesh_triangles).c_str(), stdout);
  } else if (a.stats) {
    std::printf("%s (seed %llu)\n%s", species.name.c_str(), a.seed, gen::stats_text(stats).c_str());
  }
  if (!a.out.empty() && !a.json) std::fprintf(stderr, "arbor: wrote %s\n", a.out.c_str());
  return 0;
}

struct RenderArgs {
  std::string scene;
  std::string exr, png, integrator;
  int spp = 0, threads = 0, width = 0, height = 0;
  std::optional<std::uint64_t> seed;
  std::optional<double> time;
  bool force = false;
  std::string ocio_config;  // the run's OCIO config (read once, in main)
};

// The weights for the EXR's arbor:treemaker_weights: one set when every tree shares it.
std::string treemaker_weights_text(const arbor::trace::Scene& scene) {
  std::string text;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const arbor::mat::TreemakerWeights& w = scene.instances[i].treemaker;
    char buf[160];
    std::snprintf(buf, sizeof buf, "ambient=%.9g lambert=%.9g height=%.9g radius=%.9g angle=%.9g",
                  w.ambient, w.lambert, w.height, w.radius, w.angle);
    if (i == 0) text = buf;
    else if (text != buf) return "per tree";
  }
  return text;
}

int run_render(const RenderArgs& a) {
  using namespace arbor;
  trace::SceneDesc scene = trace::load_scene(a.scene);
  trace::RenderSettings& r = scene.render;
  if (!a.integrator.empty()) r.integrator = a.integrator;
  // --spp sets the sample count of the integrator in use (the scene keeps one for each).
  const bool treemaker = r.integrator == "treemaker";
  if (a.spp > 0) (treemaker ? r.treemaker_spp : r.spp) = a.spp;
  if (a.width > 0) r.width = a.width;
  if (a.height > 0) r.height = a.height;
  if (a.seed) r.seed = *a.seed;
  r.threads = a.threads;
  if (a.time) {
    for (trace::TreeDesc& t : scene.trees) t.time = *a.time;
  }
  if (!a.exr.empty()) scene.output.exr = a.exr;
  if (!a.png.empty()) scene.output.png = a.png;
  if (!treemaker &&
      std::find(scene.output.aovs.begin(), scene.output.aovs.end(), "treemaker") != scene.output.aovs.end()) {
    throw InputError(scene.output.treemaker_aov_where,
                     "output.aovs lists \"treemaker\", which only the treemaker integrator writes "
                     "(render it with --integrator treemaker)");
  }
  if (scene.output.exr.empty() && scene.output.png.empty()) {
    throw InputError({a.scene, 0, 0}, "nothing to write: give -o OUT.exr, --png OUT.png or an [output] table");
  }
  if (!scene.output.exr.empty() && !ends_with(scene.output.exr, ".exr")) {
    throw InputError({}, "the EXR output must end in .exr: " + scene.output.exr);
  }
  if (!scene.output.png.empty() && !ends_with(scene.output.png, ".png")) {
    throw InputError({}, "the PNG output must end in .png: " + scene.output.png);
  }
  const std::vector<std::string> inputs = trace::scene_inputs(scene);
  if (!scene.output.exr.empty()) refuse_overwriting("the EXR output", scene.output.exr, inputs);
  if (!scene.output.png.empty()) {
    refuse_overwriting("the PNG output", scene.output.png, inputs, {scene.output.exr});
  }
  for (const std::string& out : {scene.output.exr, scene.output.png}) {
    if (!out.empty()) check_output_folder(out);
  }
  trace::check_render_memory(scene, a.force);
  const trace::ColorPipeline color(a.ocio_config);
  color.check(scene.output);
  const trace::EmbreeDevice device(r.threads > 0 ? "threads=" + std::to_string(r.threads) : "");
  Progress build_progress("build", 1);
  const std::unique_ptr<const trace::Scene> built = trace::build_scene(scene, color.config_path(), &build_progress);
  const trace::World world(*built, device);
  build_progress.finish();
  const trace::Sky sky(scene.sky, scene.sun, color.xyz_to_scene_linear());
  Progress progress("render", 1);
  trace::RenderStats stats;
  const trace::Image image =
      treemaker ? trace::render_treemaker(scene, world, sky, color.to_output(scene.output.colorspace), &progress, stats)
                : trace::render_path(scene, world, sky, color.to_output(scene.output.colorspace), &progress, stats);
  progress.finish();
  const int spp = treemaker ? r.treemaker_spp : r.spp;
  trace::ExrMetadata meta{scene.path, r.seed, spp, r.integrator, stats, {}};
  if (treemaker) meta.treemaker_weights = treemaker_weights_text(*built);
  if (!scene.output.exr.empty()) trace::write_exr(image, scene.output, meta, scene.output.exr);
  if (!scene.output.png.empty()) trace::write_png(image, scene.output, color, scene.output.png);
  const double seconds = std::max(stats.seconds, 1e-9);
  std::fprintf(stderr,
               "arbor: rendered %dx%d at %d spp in %.2f s (%.3g samples/s, %.3g rays/s; %zu trees "
               "from %zu prototypes, built in %.2f s)\n",
               r.width, r.height, spp, stats.seconds, double(stats.samples) / seconds,
               double(stats.rays) / seconds, built->stats.instances, built->stats.prototypes,
               built->stats.build_seconds + world.build_seconds());
  if (stats.nonfinite > 0) {
    std::fprintf(stderr, "arbor: warning: %llu samples were NaN or infinite and were left out\n",
                 static_cast<unsigned long long>(stats.nonfinite));
  }
  for (const std::string& out : {scene.output.exr, scene.output.png}) {
    if (!out.empty()) std::fprintf(stderr, "arbor: wrote %s\n", out.c_str());
  }
  return 0;
}

struct CompareArgs {
  std::string a, b;
  std::string heatmap, side_by_side;
  std::string display = "sRGB", view = "ACES 1.0 SDR-video";
  bool json = false, reference_test = false, fit_treemaker = false;
  std::string ocio_config;
};

// A number for JSON: infinities (PSNR of identical images) have no JSON spelling, so null.
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void check_image_output(const std::string& path, const CompareArgs& a, const char* option) {
  if (path.empty()) return;
  refuse_overwriting(option, path, {a.a, a.b});
  if (!OIIO::ImageOutput::create(path)) {
    throw arbor::InputError({}, std::string(option) + " " + path +
                                    ": no image format for this extension (use .png, .exr, .tif or .jpg)");
  }
  arbor::check_output_folder(path);
}

int run_compare(const CompareArgs& args) {
  using namespace arbor;
  check_image_output(args.heatmap, args, "--heatmap");
  check_image_output(args.side_by_side, args, "--side-by-side");
  if (!args.heatmap.empty()) refuse_overwriting("--heatmap", args.heatmap, {}, {args.side_by_side});
  const trace::CompareImage a = trace::read_compare_image(args.a);
  const trace::CompareImage b = trace::read_compare_image(args.b);
  const trace::CompareMetrics m = trace::compare_images(a, b);
  trace::ZTest z;
  if (args.reference_test) z = trace::reference_z_test(a, b);
  // --fit-treemaker: whichever image carries the treemaker AOVs is the approximate render, the
  // other the exact one.
  trace::TreemakerFit fit;
  std::string exact_path, approx_path;
  if (args.fit_treemaker) {
    const bool a_tm = trace::has_treemaker_aovs(args.a), b_tm = trace::has_treemaker_aovs(args.b);
    if (a_tm == b_tm) {
      throw InputError({}, std::string("--fit-treemaker needs one exact render and one treemaker render "
                                       "with the \"treemaker\" AOVs; ") +
                               (a_tm ? "both images have them" : "neither image has them"));
    }
    exact_path = a_tm ? args.b : args.a;
    approx_path = a_tm ? args.a : args.b;
    const trace::CompareImage& exact = a_tm ? b : a;
    if (exact.colorspace.empty()) {
      std::fprintf(stderr, "arbor compare: note: %s does not say its colour space (no arbor:colorspace); "
                           "the fit takes it to be scene-linear in the treemaker render's space\n",
                   exact_path.c_str());
    }
    fit = trace::fit_treemaker(exact, trace::read_treemaker_aovs(approx_path));
  }
  trace::write_compare_pictures(a, b, {args.heatmap, args.side_by_side, args.display, args.view, args.ocio_config});
  const auto& names = trace::kTreemakerTermNames;
  if (args.json) {
    std::printf("{\"rmse\": %s, \"mean_abs\": %s, \"rel_mse\": %s, \"max_abs\": %s, "
                "\"max_at\": [%d, %d], \"psnr\": %s",
                json_number(m.rmse).c_str(), json_number(m.mean_abs).c_str(),
                json_number(m.rel_mse).c_str(), json_number(m.max_abs).c_str(), m.max_x, m.max_y,
                json_number(m.psnr).c_str());
    if (args.reference_test) {
      std::printf(", \"z_test_pass_fraction\": %s, \"z_critical\": %s, \"pixels\": %lld, "
                  "\"failed_pixels\": %lld, \"passed\": %s",
                  json_number(z.pass_fraction).c_str(), json_number(z.z_critical).c_str(), z.pixels,
                  z.failed, z.passed ? "true" : "false");
    }
    if (args.fit_treemaker) {
      std::printf(", \"treemaker_fit\": {\"exact\": \"%s\", \"approximate\": \"%s\", \"weights\": {",
                  json_escape(exact_path).c_str(), json_escape(approx_path).c_str());
      for (int i = 0; i < 5; ++i) {
        std::printf("%s\"%s\": %s", i ? ", " : "", names[i], json_number(fit.weights[static_cast<size_t>(i)]).c_str());
      }
      std::printf("}, \"pixels\": %lld, \"rmse\": %s, \"rel_mse\": %s, \"render_rmse\": %s, "
                  "\"render_rel_mse\": %s, \"render_weights\": \"%s\"}",
                  fit.pixels, json_number(fit.rmse).c_str(), json_number(fit.rel_mse).c_str(),
                  json_number(fit.render_rmse).c_str(), json_number(fit.render_rel_mse).c_str(),
                  json_escape(fit.render_weights).c_str());
    }
    std::printf("}\n");
  } else {
    std::printf("rmse      %.6g\nmean_abs  %.6g\nrel_mse   %.6g\nmax_abs   %.6g at (%d, %d)\n",
                m.rmse, m.mean_abs, m.rel_mse, m.max_abs, m.max_x, m.max_y);
    if (std::isfinite(m.psnr)) {
      std::printf("psnr      %.2f dB\n", m.psnr);
    } else {
      std::printf("psnr      inf (identical)\n");
    }
    if (args.reference_test) {
      std::printf("z-test    %.3f %% of %lld pixels pass (|z| <= %.2f: alpha 0.01, Sidak-corrected); "
                  "needs %.1f %%: %s\n",
                  100.0 * z.pass_fraction, z.pixels, z.z_critical, 100.0 * z.required,
                  z.passed ? "PASS" : "FAIL");
    }
    if (args.fit_treemaker) {
      std::printf("treemaker fit of %s to the exact %s, over the %lld pixels that show a tree:\n",
                  approx_path.c_str(), exact_path.c_str(), fit.pixels);
      std::printf("  fitted weights  ");
      for (int i = 0; i < 5; ++i) std::printf(" %s=%.4g", names[i], fit.weights[static_cast<size_t>(i)]);
      std::printf("\n  fitted          rmse %.6g  rel_mse %.6g\n", fit.rmse, fit.rel_mse);
      std::printf("  as rendered     rmse %.6g  rel_mse %.6g  (%s)\n", fit.render_rmse,
                  fit.render_rel_mse, fit.render_weights.empty() ? "weights unknown" : fit.render_weights.c_str());
      for (int i = 0; i < 5; ++i) {
        if (!fit.determined[static_cast<size_t>(i)]) {
          std::printf("  note: the %s factor is 0 wherever a tree is seen, so its weight is not determined\n", names[i]);
        }
      }
      std::printf("  as a scene table:\n  [tree.treemaker]\n");
      for (int i = 0; i < 5; ++i) std::printf("  %s = %.4f\n", names[i], fit.weights[static_cast<size_t>(i)]);
    }
  }
  if (args.reference_test && !z.a_has_variance) {
    std::fprintf(stderr, "arbor compare: note: %s has no variance channels; the test used the "
                         "reference's variance alone\n", args.a.c_str());
  }
  return args.reference_test && !z.passed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"arbor " ARBOR_VERSION_STRING
               ": grows trees from procedural models and renders them (physically based)"};
  app.set_version_flag("--version", std::string("arbor ") + ARBOR_VERSION_STRING);
  app.require_subcommand(1);

  GrowArgs grow;
  CLI::App* grow_cmd = app.add_subcommand(
      "grow", "Grow a tree from a species file and report or export it");
  grow_cmd->add_option("SPECIES", grow.species,
                       "species file: .toml (model = weber-penn or fractal), .xml (Arbaro), .lsys (L-system), .tmpl (TREE-MAKER) or .skel (skeleton)")
      ->required();
  grow_cmd->add_option("--seed", grow.seed, "random seed (same seed, same tree)")
      ->check(seed_check())
      ->capture_default_str();
  grow_cmd->add_option("--time", grow.time, "seconds of wind sway (needs WindSpeed/WindGust)")
      ->check(finite_in(-1e6, 1e6))
      ->capture_default_str();
  grow_cmd->add_option("--quality", grow.quality,
                       "leaf quality factor: leaf count x Q, leaf size / sqrt(Q)")
      ->check(finite_in(1e-6, 100.0))
      ->capture_default_str();
  grow_cmd->add_option("-o,--output", grow.out,
                       "write the tree: .obj or .ply (tessellated mesh, bark and leaf groups), "
                       ".pbrt (pbrt-v4, limbs as curves) or .skel (skeleton file)");
  grow_cmd->add_flag("--stats", grow.stats, "print statistics of the tree");
  grow_cmd->add_flag("--json", grow.json, "print the statistics as one JSON object");
  grow_cmd->add_flag("--force", grow.force,
                     "grow even a tree estimated at over 10 million stems or 100 million leaves");

  RenderArgs render;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a scene file to EXR/PNG (path tracer, or TREE-MAKER's shading)");
  render_cmd->add_option("SCENE", render.scene, "scene file (.toml)")->required();
  render_cmd->add_option("-o,--output", render.exr, "EXR to write (overrides [output] exr)");
  render_cmd->add_option("--png", render.png, "PNG to write through the display view");
  render_cmd->add_option("--spp", render.spp, "samples per pixel of the integrator in use "
                         "(overrides render.spp, or render.treemaker_spp for treemaker)")->check(CLI::Range(1, 1 << 20));
  render_cmd->add_option("--seed", render.seed, "random seed (overrides render.seed)")->check(seed_check());
  render_cmd->add_option("--threads", render.threads, "threads (0: all cores)")->check(CLI::Range(0, 1024));
  render_cmd->add_option("--integrator", render.integrator, "path (exact) or treemaker (TREE-MAKER's approximate shading)")
      ->check(CLI::IsMember({"path", "treemaker"}));
  render_cmd->add_option("--width", render.width, "image width")->check(CLI::Range(1, 16384));
  render_cmd->add_option("--height", render.height, "image height")->check(CLI::Range(1, 16384));
  render_cmd->add_option("--time", render.time, "seconds of wind sway for every [[tree]]")
      ->check(finite_in(-1e6, 1e6));
  render_cmd->add_flag("--force", render.force,
                       "render even when the image and trees are estimated to need more memory "
                       "than this machine (or ulimit) allows");
  CompareArgs cmp;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare", "Compare image A against reference B: error metrics, heatmap, z-test");
  compare_cmd->add_option("A", cmp.a, "image to test (EXR, or any format OIIO reads)")->required();
  compare_cmd->add_option("B", cmp.b, "reference image (with variance.R/G/B for --reference-test)")
      ->required();
  compare_cmd->add_option("--heatmap", cmp.heatmap,
                          "write a false-colour image of the per-pixel error with a scale bar");
  compare_cmd->add_option("--side-by-side", cmp.side_by_side,
                          "write A, B and the heatmap in one picture through the display view");
  compare_cmd->add_option("--display", cmp.display, "OCIO display for --side-by-side")
      ->capture_default_str();
  compare_cmd->add_option("--view", cmp.view, "OCIO view for --side-by-side")->capture_default_str();
  compare_cmd->add_flag("--json", cmp.json, "print the metrics as one JSON object");
  compare_cmd->add_flag("--reference-test", cmp.reference_test,
                        "per-pixel z-test against B's variance (alpha 0.01, Sidak-corrected); "
                        "exit 0 when at least 99.5 % of pixels pass, 1 otherwise");
  compare_cmd->add_flag("--fit-treemaker", cmp.fit_treemaker,
                        "fit the five TREE-MAKER weights by least squares: one image is an exact "
                        "render, the other a treemaker render of the same view with the \"treemaker\" "
                        "AOVs; prints the weights and the error left");

  arbor::remove_temporaries_on_signal();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    // The OCIO config of this run: $OCIO, or arbor's own beside the executable.
    render.ocio_config = cmp.ocio_config = arbor::trace::default_ocio_config();
    if (*grow_cmd) return run_grow(grow);
    if (*render_cmd) return run_render(render);
    if (*compare_cmd) return run_compare(cmp);
  } catch (const arbor::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const arbor::RuntimeFailure& e) {
    std::fprintf(stderr, "arbor: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "arbor: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "arbor: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
