// `arbor grow`: load, grow, measure, export.
#include "app/commands/grow.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

#include "app/commands/options.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/progress.h"
#include "common/strings.h"
#include "tracer/film_file.h"
#include "formats/species_file.h"
#include "generator/export/export_mesh.h"
#include "generator/export/export_pbrt.h"
#include "generator/export/skeleton_file.h"
#include "generator/export/tree_stats.h"
#include "generator/geometry/geometry_plan.h"
#include "generator/geometry/tree_geometry.h"
#include "generator/geometry/tree_mesh.h"
#include "generator/grow.h"

namespace arbor::app {

CLI::App* add_grow_command(CLI::App& app, GrowRequest& grow) {
  CLI::App* cmd =
      app.add_subcommand("grow", "Grow a tree from a species file and report or export it");
  cmd->add_option("SPECIES", grow.species,
                  "species file: .toml (model = weber-penn or fractal), .xml (Arbaro), .lsys "
                  "(L-system), .tmpl (TREE-MAKER) or .skel (skeleton)")
      ->required();
  cmd->add_option("--seed", grow.seed, "random seed (same seed, same tree)")
      ->check(seed_check())
      ->capture_default_str();
  cmd->add_option(
         "--time", grow.time,
         "Weber & Penn species: seconds of wind sway (needs WindSpeed/WindGust); fractal "
         "(time-aware) trees: the age in years (0: the species' own age); other models ignore it")
      ->check(finite_in(-1e6, 1e6))
      ->capture_default_str();
  cmd->add_option("--quality", grow.quality,
                  "leaf quality factor: leaf count x Q, leaf size / sqrt(Q)")
      ->check(finite_in(1e-6, 100.0))
      ->capture_default_str();
  cmd->add_option("-o,--output", grow.out,
                  "write the tree: .obj (tessellated mesh, bark and leaf groups, with a .mtl "
                  "beside it) or .ply (binary), .pbrt (pbrt-v4, limbs as curves) or .skel "
                  "(skeleton file)");
  cmd->add_option("--up", grow.up,
                  "up axis of the .obj, .ply or .pbrt: z (arbor's) or y "
                  "(Blender's OBJ importer, Maya, game engines)")
      ->check(CLI::IsMember({"z", "y"}))
      ->capture_default_str();
  cmd->add_flag("--stats", grow.stats,
                "print statistics of the tree (the default without -o or --json; height and crown "
                "width are its envelope's: an upper "
                "bound within a few cm) and its render geometry's counts, counted without "
                "building it; with -o to a mesh or .pbrt also the geometry's size in bytes");
  cmd->add_flag("--json", grow.json, "print the statistics as one JSON object");
  cmd->add_flag("--force", grow.force,
                "grow even a tree estimated at over 10 million stems or 100 million leaves");
  return cmd;
}

namespace {

// Refuses a request that cannot be carried out before any work, and returns its up axis.
generator::UpAxis validate(const GrowRequest& a) {
  if (!a.out.empty() && !ends_with(a.out, ".obj") && !ends_with(a.out, ".ply") &&
      !ends_with(a.out, ".pbrt") && !ends_with(a.out, ".skel")) {
    throw InputError({}, "-o " + a.out + ": the output must be .obj, .ply, .pbrt or .skel");
  }
  if (a.up != "z" && a.up != "y")
    throw InputError({}, "--up " + a.up + ": the up axis must be z or y");
  const generator::UpAxis up = a.up == "y" ? generator::UpAxis::Y : generator::UpAxis::Z;
  if (up == generator::UpAxis::Y && ends_with(a.out, ".skel")) {
    throw InputError({},
                     "--up y: a skeleton file is arbor's own input and always z-up; --up is for "
                     ".obj, .ply and .pbrt");
  }
  if (!a.out.empty()) {
    refuse_overwriting("-o", a.out, {a.species});
    if (ends_with(a.out, ".obj"))
      refuse_overwriting("-o", generator::mtl_path_for(a.out), {a.species});
    prepare_output_folder(a.out);
  }
  return up;
}

// Says on stderr when --time or --quality would change nothing for this species' model, rather
// than ignore them silently.
void note_ignored_options(const GrowRequest& a, const generator::Species& species) {
  using generator::Model;
  const Model model = species.model();
  const char* time_ignored = nullptr;
  if (model == Model::WeberPenn && species.weber_penn().wind_speed == 0.0 &&
      species.weber_penn().wind_gust == 0.0)
    time_ignored = "the species has no wind (WindSpeed and WindGust are 0), so nothing sways";
  else if (model != Model::WeberPenn && model != Model::Fractal)
    time_ignored = "only Weber & Penn species (wind sway) and fractal trees (age) have a time";
  if (a.time != 0.0 && time_ignored) {
    std::fprintf(stderr, "arbor: warning: --time %s does nothing for %s: %s\n",
                 tracer::number_text(a.time).c_str(), a.species.c_str(), time_ignored);
  }
  if (a.quality != 1.0 && model != Model::WeberPenn) {
    std::fprintf(stderr,
                 "arbor: warning: --quality %s does nothing for %s: only Weber & Penn species "
                 "have the paper's leaf quality (§4.5)\n",
                 tracer::number_text(a.quality).c_str(), a.species.c_str());
  }
}

// "698 MB": a written file's size, so that a large export does not pass unnoticed.
std::string size_text(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return "";
  char buf[48];
  if (bytes >= 1000000)
    std::snprintf(buf, sizeof buf, " (%.0f MB)", static_cast<double>(bytes) / 1e6);
  else
    std::snprintf(buf, sizeof buf, " (%.0f kB)", static_cast<double>(bytes) / 1e3);
  return buf;
}

}  // namespace

int grow_command(const GrowRequest& a) {
  const generator::UpAxis up = validate(a);
  generator::Species species = formats::load_species(a.species);
  for (const std::string& w : species.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  note_ignored_options(a, species);
  // With nothing else asked, grow reports the tree (as --stats).
  const bool report = a.stats || (a.out.empty() && !a.json);

  Progress progress("grow", 1);
  generator::GrowOptions options;
  options.seed = a.seed;
  options.time = a.time;
  options.quality = a.quality;
  options.force = a.force;
  options.progress = &progress;
  const auto start = std::chrono::steady_clock::now();
  generator::Skeleton skeleton;
  try {
    skeleton = generator::grow_tree(species, options);
  } catch (const RuntimeFailure& e) {
    // Refusing an absurd size is about the input: report it against the species file.
    throw InputError({a.species, 0, 0}, e.what());
  }
  progress.finish();
  generator::TreeStats stats = generator::compute_stats(skeleton);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  long long mesh_triangles = -1;
  // A skeleton file needs only the skeleton; the statistics and the meshes need the geometry.
  if (ends_with(a.out, ".skel")) generator::write_skeleton_file(skeleton, a.out);
  const bool exports_geometry = !a.out.empty() && !ends_with(a.out, ".skel");
  const auto geometry_start = std::chrono::steady_clock::now();
  auto geometry_seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - geometry_start).count();
  };
  if ((report || a.json) && !exports_geometry) {
    // The statistics alone: the geometry's counts, without building it (issue 31).
    const generator::GeometryStats counts =
        generator::count_tree_geometry(skeleton, generator::geometry_options_for(species));
    generator::add_geometry_stats(stats, counts, geometry_seconds());
  }
  if (exports_geometry) {
    const generator::TreeGeometry geometry =
        generator::build_tree_geometry(skeleton, generator::geometry_options_for(species));
    generator::add_geometry_stats(stats, geometry.stats, geometry_seconds());
    if (ends_with(a.out, ".pbrt")) {
      generator::write_pbrt(geometry, species.bark, species.leaf, a.out, up);
    } else if (!a.out.empty()) {
      const generator::TreeMesh mesh = generator::tessellate(geometry);
      mesh_triangles = static_cast<long long>(mesh.triangle_count());
      const generator::MeshLooks looks{species.name, species.bark, species.leaf};
      if (ends_with(a.out, ".obj"))
        generator::write_obj(mesh, a.out, looks, up);
      else
        generator::write_ply(mesh, a.out, looks, up);
    }
  }
  if (a.json) {
    std::fputs(generator::stats_json(stats, species.name, a.seed, mesh_triangles).c_str(), stdout);
  } else if (report) {
    std::printf("%s (seed %llu)\n%s", species.name.c_str(), static_cast<unsigned long long>(a.seed),
                generator::stats_text(stats).c_str());
  }
  if (!a.out.empty() && !a.json) {
    if (ends_with(a.out, ".obj")) {
      std::fprintf(stderr, "arbor: wrote %s%s and %s\n", a.out.c_str(), size_text(a.out).c_str(),
                   generator::mtl_path_for(a.out).c_str());
    } else {
      std::fprintf(stderr, "arbor: wrote %s%s\n", a.out.c_str(), size_text(a.out).c_str());
    }
  }
  return 0;
}

}  // namespace arbor::app
