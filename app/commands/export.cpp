// `arbor export`: load the scene, apply the overrides, check the outputs, write the pbrt-v4
// scene, report.
#include "app/commands/export.h"

#include <cstdio>
#include <memory>
#include <vector>

#include "app/commands/metering.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/progress.h"
#include "common/strings.h"
#include "formats/scene_file.h"
#include "imaging/color.h"
#include "scene/frame.h"
#include "scene/render_input.h"
#include "scene/scene.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"
#include "tracer/exposure.h"
#include "tracer/lights/sky.h"
#include "tracer/pbrt_scene.h"

namespace arbor::app {

using tracer::EmbreeDevice;
using tracer::ground_path_for;
using tracer::kSkyMapWidth;
using tracer::pbrt_color_space_of;
using tracer::PbrtExport;
using tracer::Sky;
using tracer::sky_path_for;
using tracer::World;
using tracer::write_pbrt_scene;

CLI::App* add_export_command(CLI::App& app, ExportRequest& exp) {
  CLI::App* cmd = app.add_subcommand("export",
                                     "Write a scene as a complete pbrt-v4 scene (camera, sun and "
                                     "sky, materials, trees, meshes, ground)");
  cmd->add_option("SCENE", exp.scene, "scene file (.toml)")->required();
  cmd->add_option("-o,--output", exp.out,
                  "the pbrt-v4 scene to write (OUT.pbrt; its sky goes beside it as OUT.sky.exr)")
      ->required();
  add_override_options(cmd, exp.overrides, kSppOption,
                       "pbrt's pixel samples (overrides render.spp)");
  cmd->add_option("--frame", exp.frame,
                  "frame N of the scene's [animation]: every tree at time N / fps")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--sky-resolution", exp.sky_resolution,
                  "texels along each side of the sky's equal-area square image")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  return cmd;
}

int export_command(const ExportRequest& a) {
  if (!ends_with(a.out, ".pbrt"))
    throw InputError({}, "-o " + a.out + ": the pbrt-v4 scene must end in .pbrt");
  if (a.sky_resolution < 16 || a.sky_resolution > 8192) {
    throw InputError(
        {}, "--sky-resolution " + std::to_string(a.sky_resolution) + " must be 16 to 8192");
  }
  spec::SceneDesc scene = formats::load_scene(a.scene);
  // pbrt renders the exact image: --spp is the path integrator's sample count.
  RenderOverrides overrides = a.overrides;
  overrides.integrator = spec::Integrator::Path;
  apply_overrides(scene, overrides);
  // A frame of an animation: its clock (the scene's own outputs are not written here).
  scene.output.exr.clear();
  scene.output.png.clear();
  scene::apply_frame(scene, a.frame);
  const std::string sky_path = sky_path_for(a.out), ground_path = ground_path_for(a.out);
  const std::vector<std::string> inputs = spec::scene_inputs(scene);
  refuse_overwriting("-o", a.out, inputs);
  refuse_overwriting("the sky beside -o", sky_path, inputs, {a.out});
  refuse_overwriting("the ground's image beside -o", ground_path, inputs, {a.out, sky_path});
  const imaging::ColorPipeline color(a.ocio_config);
  pbrt_color_space_of(color);  // refused before anything is made
  prepare_output_folder(a.out);

  Progress build_progress("build", 1);
  const std::unique_ptr<const scene::Scene> built =
      scene::build_scene(scene, color.config_path(), &build_progress);
  build_progress.finish();
  scene::RenderInput input = scene::render_input(scene);
  if (input.camera.auto_exposure) {
    // pbrt has no meter: the exposure arbor's render meters, written as a fixed scale.
    const EmbreeDevice device("");
    const Sky sky(input.sky, input.sun, color.xyz_to_scene_linear(), kSkyMapWidth,
                  input.render.aerial_perspective);
    const double frame_zero =
        meters_frame_zero(scene, input)
            ? frame_zero_exposure(scene, input, sky, {&device, color.config_path()})
            : 0.0;
    const World world(*built, device);
    input = with_scene_exposure(scene, input, world, sky, frame_zero);
  }
  const PbrtExport result = write_pbrt_scene(*built, input, color, a.out, a.sky_resolution);
  for (const std::string& c : result.clamped) {
    std::fprintf(stderr, "arbor: warning: %s is outside [0, 1] in pbrt's %s space; clamped\n",
                 c.c_str(), result.space.c_str());
  }
  std::string files;
  for (const std::string& f : result.written) files += (files.empty() ? "" : ", ") + f;
  std::fprintf(stderr, "arbor: wrote %s\n", files.c_str());
  return 0;
}

}  // namespace arbor::app
