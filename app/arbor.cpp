// The arbor command line: parses arguments with CLI11, calls the libraries' commands (scene/
// grow_command, tracer/render_command, imaging/compare_command), maps errors to exit codes
// (0 success, 1 the work failed, 2 bad input or usage).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "arbor/version.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "imaging/color.h"
#include "imaging/compare_command.h"
#include "scene/grow_command.h"
#include "tracer/export_command.h"
#include "tracer/merge_command.h"
#include "tracer/plan_command.h"
#include "tracer/render_command.h"

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

// CLI11 check of an option that takes text: an empty value is refused (an empty --crop once
// rendered the whole image over the scene's outputs).
CLI::Validator non_empty() {
  return CLI::Validator([](std::string& v) { return v.empty() ? std::string("needs a value, not an empty one") : std::string(); },
                        "");
}

// Levenshtein distance, for "did you mean" on a mistyped command.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"arbor " ARBOR_VERSION_STRING
               ": grows trees from procedural models and renders them (physically based)"};
  app.set_version_flag("--version", std::string("arbor ") + ARBOR_VERSION_STRING + " (commit " + ARBOR_COMMIT + ")");
  app.require_subcommand(1);

  arbor::trace::GrowRequest grow;
  CLI::App* grow_cmd = app.add_subcommand(
      "grow", "Grow a tree from a species file and report or export it");
  grow_cmd->add_option("SPECIES", grow.species,
                       "species file: .toml (model = weber-penn or fractal), .xml (Arbaro), .lsys (L-system), .tmpl (TREE-MAKER) or .skel (skeleton)")
      ->required();
  grow_cmd->add_option("--seed", grow.seed, "random seed (same seed, same tree)")
      ->check(seed_check())
      ->capture_default_str();
  grow_cmd->add_option("--time", grow.time,
                       "Weber & Penn species: seconds of wind sway (needs WindSpeed/WindGust); fractal "
                       "(time-aware) trees: the age in years (0: the species' own age); other models ignore it")
      ->check(finite_in(-1e6, 1e6))
      ->capture_default_str();
  grow_cmd->add_option("--quality", grow.quality,
                       "leaf quality factor: leaf count x Q, leaf size / sqrt(Q)")
      ->check(finite_in(1e-6, 100.0))
      ->capture_default_str();
  grow_cmd->add_option("-o,--output", grow.out,
                       "write the tree: .obj (tessellated mesh, bark and leaf groups, with a .mtl "
                       "beside it) or .ply (binary), .pbrt (pbrt-v4, limbs as curves) or .skel "
                       "(skeleton file)");
  grow_cmd->add_option("--up", grow.up, "up axis of the .obj, .ply or .pbrt: z (arbor's) or y "
                       "(Blender's OBJ importer, Maya, game engines)")
      ->check(CLI::IsMember({"z", "y"}))
      ->capture_default_str();
  grow_cmd->add_flag("--stats", grow.stats,
                     "print statistics of the tree (height and crown width are its envelope's: an upper "
                     "bound within a few cm)");
  grow_cmd->add_flag("--json", grow.json, "print the statistics as one JSON object");
  grow_cmd->add_flag("--force", grow.force,
                     "grow even a tree estimated at over 10 million stems or 100 million leaves");

  arbor::trace::RenderRequest render;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a scene file to EXR/PNG (path tracer, or TREE-MAKER's shading)");
  render_cmd->add_option("SCENE", render.scene, "scene file (.toml)")->required();
  render_cmd->add_option("-o,--output", render.exr, "EXR to write: replaces the scene's [output] exr and png (a PNG is then written only with --png)");
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
  render_cmd->add_option("--frame", render.frame,
                         "render frame N of the scene's [animation]: every tree at time N / fps, the "
                         "frame's own seed (unless animation.pin_seed), N in place of #### in the outputs")
      ->check(CLI::Range(0, 1000000));
  render_cmd->add_flag("--force", render.force,
                       "render even when the image and trees are estimated to need more memory "
                       "than this machine (or ulimit) allows");
  render_cmd->add_flag("--resume", render.resume,
                       "continue the render from the film state beside its EXR (OUT.exr.state), to the "
                       "image an uninterrupted render gives");
  render_cmd->add_flag("--transparent", render.transparent,
                       "camera rays that escape to the sky add nothing and leave alpha 0 (premultiplied "
                       "RGBA, for compositing; sets output.transparent_sky)");
  render_cmd->add_option("--time-limit", render.time_limit,
                         "seconds: stop after the last pass that fits (at least one pass is rendered; 0: no limit)")
      ->check(finite_in(0.0, 1e9));
  render_cmd->add_option("--checkpoint-seconds", render.checkpoint_seconds,
                         "rewrite the outputs this often as passes finish (overrides output.checkpoint_seconds)")
      ->check(finite_in(0.0, 1e7));
  render_cmd->add_option("--passes", render.passes,
                         "A:B: render only passes A to B-1 (a work unit for arbor merge; needs -o)")
      ->check(non_empty());
  render_cmd->add_option("--crop", render.crop,
                         "X0,Y0,X1,Y1: render only that window (pixels, end exclusive), each pixel as in the "
                         "whole image (needs -o)")
      ->check(non_empty());
  arbor::trace::CompareRequest cmp;
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

  arbor::trace::MergeRequest merge;
  CLI::App* merge_cmd = app.add_subcommand(
      "merge", "Combine work units of one render (--passes ranges, --crop windows) into its image, bit for bit");
  merge_cmd->add_option("PARTS", merge.parts,
                        "the parts' EXRs, in any order (each with its film state PART.exr.state beside it)")
      ->required();
  merge_cmd->add_option("-o,--output", merge.exr, "the merged EXR")->required();
  merge_cmd->add_option("--png", merge.png, "also write a PNG of it through the display view");

  arbor::trace::PlanRequest plan;
  CLI::App* plan_cmd = app.add_subcommand(
      "plan", "Split a render into work units for any scheduler: prints one shell command per unit, then the merge(s)");
  plan_cmd->add_option("SCENE", plan.scene, "scene file (.toml)")->required();
  plan_cmd->add_option("-o,--output", plan.exr,
                       "the merged EXR (with --frames, a run of # takes the frame number: out.####.exr); "
                       "the parts go in OUT.parts/ beside it")
      ->required();
  plan_cmd->add_option("--png", plan.png, "the merged PNG (with #### for --frames)");
  plan_cmd->add_option("--tiles", plan.tiles, "CxR: crop windows in C columns and R rows")->capture_default_str();
  plan_cmd->add_option("--pass-groups", plan.pass_groups, "K: each tile's passes in K contiguous runs")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  plan_cmd->add_option("--frames", plan.frames, "A:B: frames A to B-1 of the scene's [animation], one merge each");
  plan_cmd->add_flag("--json", plan.json, "print the plan as one JSON object (units, merges, argv and shell lines)");
  plan_cmd->add_option("--width", plan.width, "image width (handed to every unit)")->check(CLI::Range(1, 16384));
  plan_cmd->add_option("--height", plan.height, "image height")->check(CLI::Range(1, 16384));
  plan_cmd->add_option("--spp", plan.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20));
  plan_cmd->add_option("--seed", plan.seed, "random seed")->check(seed_check());
  plan_cmd->add_option("--integrator", plan.integrator, "path or treemaker")->check(CLI::IsMember({"path", "treemaker"}));
  plan_cmd->add_option("--time", plan.time, "seconds of wind sway for every [[tree]]")->check(finite_in(-1e6, 1e6));
  plan_cmd->add_flag("--transparent", plan.transparent, "transparent sky (alpha 0 where camera rays escape)");

  arbor::trace::ExportRequest exp;
  CLI::App* export_cmd = app.add_subcommand(
      "export", "Write a scene as a complete pbrt-v4 scene (camera, sun and sky, materials, trees, meshes, ground)");
  export_cmd->add_option("SCENE", exp.scene, "scene file (.toml)")->required();
  export_cmd->add_option("-o,--output", exp.out,
                         "the pbrt-v4 scene to write (OUT.pbrt; its sky goes beside it as OUT.sky.exr)")
      ->required();
  export_cmd->add_option("--width", exp.width, "image width (overrides render.width)")->check(CLI::Range(1, 16384));
  export_cmd->add_option("--height", exp.height, "image height (overrides render.height)")->check(CLI::Range(1, 16384));
  export_cmd->add_option("--spp", exp.spp, "pbrt's pixel samples (overrides render.spp)")->check(CLI::Range(1, 1 << 20));
  export_cmd->add_option("--time", exp.time, "seconds of wind sway for every [[tree]]")->check(finite_in(-1e6, 1e6));
  export_cmd->add_option("--frame", exp.frame, "frame N of the scene's [animation]: every tree at time N / fps")
      ->check(CLI::Range(0, 1000000));
  export_cmd->add_option("--sky-resolution", exp.sky_resolution,
                         "texels along each side of the sky's equal-area square image")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();

  arbor::remove_temporaries_on_signal();
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Every diagnostic has one form: "arbor: error: ..." (or "FILE:LINE:COL: error: ...").
    const std::string first = argc > 1 ? argv[1] : "";
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
    const bool unknown_command = !first.empty() && first[0] != '-' &&
                                 std::find(names.begin(), names.end(), first) == names.end();
    if (unknown_command) {
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      std::string near;
      for (const std::string& n : names) {
        if (near.empty() && edit_distance(first, n) <= 2) near = n;
      }
      std::fprintf(stderr, "arbor: error: unknown command '%s'%s; the commands are %s (arbor --help)\n", first.c_str(),
                   near.empty() ? "" : (" (did you mean '" + near + "'?)").c_str(), list.c_str());
    } else {
      const bool known = std::find(names.begin(), names.end(), first) != names.end();
      std::fprintf(stderr, "arbor: error: %s (arbor %s--help)\n", e.what(), known ? (first + " ").c_str() : "");
    }
    return 2;
  }

  try {
    // The OCIO config of this run: $OCIO, or arbor's own beside the executable.
    render.ocio_config = cmp.ocio_config = merge.ocio_config = exp.ocio_config =
        arbor::trace::default_ocio_config();
    if (*grow_cmd) return arbor::trace::grow_command(grow);
    if (*render_cmd) return arbor::trace::render_command(render);
    if (*compare_cmd) return arbor::trace::compare_command(cmp);
    if (*merge_cmd) return arbor::trace::merge_command(merge);
    if (*export_cmd) return arbor::trace::export_command(exp);
    if (*plan_cmd) return arbor::trace::plan_command(plan);
  } catch (const arbor::InputError& e) {
    std::fprintf(stderr, "%s%s\n", e.where().path.empty() ? "arbor: " : "", e.what());
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
