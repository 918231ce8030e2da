// `arbor plan`: tiles × pass groups (× frames) as `arbor render` commands, then the merges.
#include "app/commands/plan.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/executable.h"
#include "common/json.h"
#include "common/parse.h"
#include "common/strings.h"
#include "formats/scene_file.h"
#include "tracer/film.h"
#include "tracer/render.h"

namespace arbor::app {

using tracer::pass_plan_for;
using tracer::PassPlan;

namespace {

std::string absolute(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(path, ec);
  return ec ? path : p.lexically_normal().string();
}

std::string json_string(const std::string& s) { return "\"" + json_escape(s) + "\""; }

std::string json_strings(const std::vector<std::string>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + json_string(v[i]);
  return out + "]";
}

// The frames of the plan: --frames A:B, checked against the [animation] and the outputs' '#'
// runs; {-1} for a still.
std::vector<int> plan_frames(const spec::SceneDesc& scene, const PlanRequest& a) {
  std::vector<int> frames;
  if (!a.frames.empty()) {
    if (scene.animation.frames == 0)
      throw InputError({scene.path, 0, 0},
                       "--frames " + a.frames + ": the scene has no [animation] table");
    const std::vector<int> range =
        parse_integers(a.frames, ':', 2, "--frames", "A:B (frames A to B-1)");
    const int first = range[0], end = range[1];
    if (first < 0 || first >= end || end > scene.animation.frames) {
      throw InputError(
          {}, "--frames " + a.frames + ": the animation has frames 0 to " +
                  std::to_string(scene.animation.frames - 1) +
                  ", so A:B needs 0 <= A < B <= " + std::to_string(scene.animation.frames));
    }
    if (a.exr.find('#') == std::string::npos ||
        (!a.png.empty() && a.png.find('#') == std::string::npos)) {
      throw InputError(
          {}, "--frames: the outputs need a run of '#' for the frame number (e.g. out.####.exr)");
    }
    for (int f = first; f < end; ++f) frames.push_back(f);
  } else {
    if (a.exr.find('#') != std::string::npos || a.png.find('#') != std::string::npos) {
      throw InputError({}, "the outputs name a frame number (#): give --frames A:B");
    }
    frames.push_back(-1);
  }
  return frames;
}

// A tile of the image: its place in the grid and the image's size.
struct Tile {
  int columns, rows, column, row, width, height;
};

// The render unit of one tile and pass range of a frame (-1: a still), its part in `folder`.
PlanStep tile_unit(const std::vector<std::string>& common, int frame, const std::string& folder,
                   const Tile& t, int pass_begin, int pass_end) {
  PlanStep u;
  u.kind = "render";
  u.frame = frame;
  u.column = t.column;
  u.row = t.row;
  u.crop[0] = static_cast<int>(static_cast<long long>(t.column) * t.width / t.columns);
  u.crop[1] = static_cast<int>(static_cast<long long>(t.row) * t.height / t.rows);
  u.crop[2] = static_cast<int>(static_cast<long long>(t.column + 1) * t.width / t.columns);
  u.crop[3] = static_cast<int>(static_cast<long long>(t.row + 1) * t.height / t.rows);
  u.pass_begin = pass_begin;
  u.pass_end = pass_end;
  u.output = folder + "tile-" + std::to_string(t.column) + "-" + std::to_string(t.row) +
             ".passes-" + std::to_string(u.pass_begin) + "-" + std::to_string(u.pass_end) + ".exr";
  u.argv = common;
  if (frame >= 0) {
    u.argv.push_back("--frame");
    u.argv.push_back(std::to_string(frame));
  }
  for (const std::string& w :
       {std::string("--crop"),
        std::to_string(u.crop[0]) + "," + std::to_string(u.crop[1]) + "," +
            std::to_string(u.crop[2]) + "," + std::to_string(u.crop[3]),
        std::string("--passes"), std::to_string(u.pass_begin) + ":" + std::to_string(u.pass_end),
        std::string("-o"), u.output}) {
    u.argv.push_back(w);
  }
  return u;
}

}  // namespace

std::string shell_line(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& w : argv) {
    if (!line.empty()) line += ' ';
    const bool plain = !w.empty() && w.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_./:,=+-@%") == std::string::npos;
    if (plain) {
      line += w;
      continue;
    }
    line += '\'';
    for (const char c : w) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

namespace {

// InputError unless the image splits into `columns` × `rows` tiles and its passes into
// --pass-groups runs.
void check_split(const PlanRequest& a, const spec::RenderSettings& r, const PassPlan& passes,
                 int columns, int rows) {
  const int width = r.width, height = r.height, spp = passes.spp;
  if (columns < 1 || rows < 1 || columns > width || rows > height) {
    throw InputError({}, "--tiles " + a.tiles + ": the " + std::to_string(width) + "x" +
                             std::to_string(height) + " image splits into 1 to " +
                             std::to_string(width) + " columns and 1 to " + std::to_string(height) +
                             " rows");
  }
  if (a.pass_groups < 1 || a.pass_groups > passes.passes()) {
    throw InputError({}, "--pass-groups " + std::to_string(a.pass_groups) + ": the render has " +
                             std::to_string(passes.passes()) + " passes (" + std::to_string(spp) +
                             " spp in passes of " + std::to_string(r.pass_spp) + "), so 1 to " +
                             std::to_string(passes.passes()) + " groups");
  }
  if (a.pass_groups > 1 && r.noise_threshold > 0.0) {
    throw InputError(
        {},
        "--pass-groups " + std::to_string(a.pass_groups) +
            ": adaptive sampling (render.noise_threshold) decides each pass from the ones before "
            "it, so its passes cannot be split; split it by --tiles only");
  }
}

}  // namespace

std::vector<PlanStep> make_plan(const PlanRequest& a) {
  if (!ends_with(a.exr, ".exr"))
    throw InputError({}, "-o " + a.exr + ": the merged output must end in .exr");
  if (!a.png.empty() && !ends_with(a.png, ".png"))
    throw InputError({}, "--png " + a.png + " must end in .png");
  const std::vector<int> grid =
      parse_integers(a.tiles, 'x', 2, "--tiles", "CxR (columns x rows, e.g. 4x2)");
  const int columns = grid[0], rows = grid[1];
  spec::SceneDesc scene = formats::load_scene(a.scene);
  apply_overrides(scene, a.overrides);
  const spec::RenderSettings& r = scene.render;
  const int width = r.width, height = r.height;
  const PassPlan passes = pass_plan_for(scene::render_input(scene).render);
  check_split(a, r, passes, columns, rows);
  const std::vector<int> frames = plan_frames(scene, a);
  // A plan is a list a person and a scheduler read: bounded (docs/farm.md, "Limits").
  const long long unit_count = static_cast<long long>(columns) * rows * a.pass_groups *
                               static_cast<long long>(frames.size());
  if (unit_count > kMaxPlanUnits ||
      static_cast<long long>(columns) * rows * a.pass_groups > kMaxMergeParts) {
    throw InputError(
        {}, "--tiles " + a.tiles + " --pass-groups " + std::to_string(a.pass_groups) + " makes " +
                std::to_string(unit_count) + " units (" +
                std::to_string(static_cast<long long>(columns) * rows * a.pass_groups) +
                " parts per merge); a plan has at most " + std::to_string(kMaxPlanUnits) +
                " units and " + std::to_string(kMaxMergeParts) + " parts per merge");
  }
  const std::vector<std::string> inputs = spec::scene_inputs(scene);
  const std::string arbor = a.arbor.empty() ? executable_path() : a.arbor;
  if (arbor.empty()) throw RuntimeFailure("cannot find the path of this arbor (/proc/self/exe)");
  std::vector<std::string> common = {arbor, "render", absolute(a.scene)};
  for (const std::string& w : override_arguments(a.overrides)) common.push_back(w);

  std::vector<PlanStep> units, merges;
  for (const int frame : frames) {
    const std::string out = absolute(frame >= 0 ? spec::frame_path(a.exr, frame) : a.exr);
    refuse_overwriting("-o", out, inputs);
    const std::string folder = out.substr(0, out.size() - 4) + ".parts/";
    PlanStep merge;
    merge.kind = "merge";
    merge.frame = frame;
    merge.output = out;
    for (int row = 0; row < rows; ++row) {
      for (int column = 0; column < columns; ++column) {
        for (int g = 0; g < a.pass_groups; ++g) {
          const PlanStep u = tile_unit(
              common, frame, folder, {columns, rows, column, row, width, height},
              g * passes.passes() / a.pass_groups, (g + 1) * passes.passes() / a.pass_groups);
          merge.inputs.push_back(u.output);
          units.push_back(u);
        }
      }
    }
    merge.argv = {arbor, "merge", "-o", out};
    if (!a.png.empty()) {
      merge.argv.push_back("--png");
      merge.argv.push_back(absolute(frame >= 0 ? spec::frame_path(a.png, frame) : a.png));
    }
    for (const std::string& p : merge.inputs) merge.argv.push_back(p);
    merges.push_back(merge);
  }
  units.insert(units.end(), merges.begin(), merges.end());
  return units;
}

CLI::App* add_plan_command(CLI::App& app, PlanRequest& plan) {
  CLI::App* cmd = app.add_subcommand("plan",
                                     "Split a render into work units for any scheduler: prints one "
                                     "shell command per unit, then the merge(s)");
  cmd->add_option("SCENE", plan.scene, "scene file (.toml)")->required();
  cmd->add_option(
         "-o,--output", plan.exr,
         "the merged EXR (with --frames, a run of # takes the frame number: out.####.exr); "
         "the parts go in OUT.parts/ beside it")
      ->required();
  cmd->add_option("--png", plan.png, "the merged PNG (with #### for --frames)");
  cmd->add_option("--tiles", plan.tiles, "CxR: crop windows in C columns and R rows")
      ->capture_default_str();
  cmd->add_option("--pass-groups", plan.pass_groups, "K: each tile's passes in K contiguous runs")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--frames", plan.frames,
                  "A:B: frames A to B-1 of the scene's [animation], one merge each");
  cmd->add_flag("--json", plan.json,
                "print the plan as one JSON object (units, merges, argv and shell lines)");
  add_override_options(
      cmd, plan.overrides,
      kSppOption | kSeedOption | kIntegratorOption | kTransparentOption | kRegularizeOption,
      "samples per pixel (handed to every unit)");
  return cmd;
}

int plan_command(const PlanRequest& a) {
  const std::vector<PlanStep> plan = make_plan(a);
  if (!a.json) {
    for (const PlanStep& s : plan) std::printf("%s\n", shell_line(s.argv).c_str());
    return 0;
  }
  std::string units, merges;
  for (const PlanStep& s : plan) {
    std::string item = "    {";
    if (s.frame >= 0) item += "\"frame\": " + std::to_string(s.frame) + ", ";
    if (s.kind == "render") {
      item +=
          "\"name\": " +
          json_string("tile-" + std::to_string(s.column) + "-" + std::to_string(s.row) +
                      ".passes-" + std::to_string(s.pass_begin) + "-" + std::to_string(s.pass_end) +
                      (s.frame >= 0 ? ".frame-" + std::to_string(s.frame) : "")) +
          ", \"tile\": [" + std::to_string(s.column) + ", " + std::to_string(s.row) +
          "], \"crop\": [" + std::to_string(s.crop[0]) + ", " + std::to_string(s.crop[1]) + ", " +
          std::to_string(s.crop[2]) + ", " + std::to_string(s.crop[3]) + "], \"passes\": [" +
          std::to_string(s.pass_begin) + ", " + std::to_string(s.pass_end) + "], ";
    } else {
      item += "\"inputs\": " + json_strings(s.inputs) + ", ";
    }
    item += "\"output\": " + json_string(s.output) + ", \"argv\": " + json_strings(s.argv) +
            ", \"shell\": " + json_string(shell_line(s.argv)) + "}";
    std::string& list = s.kind == "render" ? units : merges;
    list += (list.empty() ? "" : ",\n") + item;
  }
  std::printf("{\n  \"scene\": %s,\n  \"units\": [\n%s\n  ],\n  \"merges\": [\n%s\n  ]\n}\n",
              json_string(absolute(a.scene)).c_str(), units.c_str(), merges.c_str());
  return 0;
}

}  // namespace arbor::app
