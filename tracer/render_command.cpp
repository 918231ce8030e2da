// `arbor render`: load the scene, apply the overrides, check the outputs, build, render, write.
#include "tracer/render_command.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/progress.h"
#include "common/strings.h"
#include "formats/scene_desc.h"
#include "imaging/color.h"
#include "imaging/image_output.h"
#include "scene/render_budget.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"
#include "tracer/render.h"
#include "tracer/lights/sky.h"

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

int render_command(const RenderRequest& a) {
  SceneDesc scene = load_scene(a.scene);
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
  const std::vector<std::string> inputs = scene_inputs(scene);
  if (!scene.output.exr.empty()) refuse_overwriting("the EXR output", scene.output.exr, inputs);
  if (!scene.output.png.empty()) {
    refuse_overwriting("the PNG output", scene.output.png, inputs, {scene.output.exr});
  }
  for (const std::string& out : {scene.output.exr, scene.output.png}) {
    if (!out.empty()) check_output_folder(out);
  }
  check_render_memory(scene, a.force);
  const ColorPipeline color(a.ocio_config);
  color.check(scene.output);
  const EmbreeDevice device(r.threads > 0 ? "threads=" + std::to_string(r.threads) : "");
  Progress build_progress("build", 1);
  const std::unique_ptr<const Scene> built = build_scene(scene, color.config_path(), &build_progress);
  const World world(*built, device);
  build_progress.finish();
  const Sky sky(scene.sky, scene.sun, color.xyz_to_scene_linear());
  Progress progress("render", 1);
  RenderStats stats;
  const Image image =
      treemaker ? render_treemaker(scene, world, sky, color.to_output(scene.output.colorspace), &progress, stats)
                : render_path(scene, world, sky, color.to_output(scene.output.colorspace), &progress, stats);
  progress.finish();
  const int spp = treemaker ? r.treemaker_spp : r.spp;
  ExrMetadata meta{scene.path, r.seed, spp, r.integrator, stats, {}};
  if (treemaker) meta.treemaker_weights = treemaker_weights_text(*built);
  if (!scene.output.exr.empty()) write_exr(image, scene.output, meta, scene.output.exr);
  if (!scene.output.png.empty()) write_png(image, scene.output, color, scene.output.png);
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

}  // namespace arbor::trace
