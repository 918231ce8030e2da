#include "app/commands/options.h"

#include <charconv>
#include <cmath>

#include "common/range.h"

namespace arbor::app {

CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& v) {
        std::uint64_t parsed = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), parsed);
        if (v.empty() || ec != std::errc() || end != v.data() + v.size()) {
          return "the seed must be a whole number from 0 to 2^64-1 (18446744073709551615), not '" +
                 v + "'";
        }
        return std::string();
      },
      "UINT64");
}

CLI::Validator finite_in(double lo, double hi) {
  const std::string range = "[" + short_number(lo) + ", " + short_number(hi) + "]";
  return CLI::Validator(
      [lo, hi, text = range](std::string& v) {
        double parsed = 0.0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), parsed);
        if (v.empty() || ec != std::errc() || end != v.data() + v.size() ||
            !std::isfinite(parsed)) {
          return "'" + v + "' is not a finite number";
        }
        if (parsed < lo || parsed > hi) return v + " is out of range " + text;
        return std::string();
      },
      "FLOAT in " + range);
}

CLI::Validator non_empty() {
  return CLI::Validator(
      [](std::string& v) {
        return v.empty() ? std::string("needs a value, not an empty one") : std::string();
      },
      "");
}

void add_override_options(CLI::App* command, RenderOverrides& o, unsigned which,
                          const std::string& spp_help) {
  command->add_option("--width", o.width, "image width (overrides render.width)")
      ->check(CLI::Range(1, 16384));
  command->add_option("--height", o.height, "image height (overrides render.height)")
      ->check(CLI::Range(1, 16384));
  if (which & kSppOption)
    command->add_option("--spp", o.spp, spp_help)->check(CLI::Range(1, 1 << 20));
  if (which & kSeedOption) {
    command->add_option("--seed", o.seed, "random seed (overrides render.seed)")
        ->check(seed_check());
  }
  if (which & kIntegratorOption) {
    command
        ->add_option_function<std::string>(
            "--integrator",
            [&o](const std::string& name) { o.integrator = spec::integrator_named(name); },
            "path (exact) or treemaker (TREE-MAKER's approximate shading)")
        ->check(CLI::IsMember(std::vector<std::string>(spec::kIntegratorNames.begin(),
                                                       spec::kIntegratorNames.end())));
  }
  command->add_option("--time", o.time, "seconds of wind sway for every [[tree]]")
      ->check(finite_in(-1e6, 1e6));
  if (which & kTransparentOption) {
    command->add_flag(
        "--transparent", o.transparent,
        "camera rays that escape to the sky add nothing and leave alpha 0 (premultiplied "
        "RGBA, for compositing; sets output.transparent_sky)");
  }
  if (which & kRegularizeOption) {
    command->add_flag("--regularize", o.regularize,
                      "after the first bounce, roughen glossy leaf coats by pbrt-v4's rule (fewer "
                      "fireflies, biased; stated in the EXR header; sets render.regularize)");
    command->add_flag("--lod", o.lod,
                      "thin each tree's limbs and leaves by its range from the camera (Weber & "
                      "Penn's degradation at range; approximate; stated in the EXR header; sets "
                      "render.lod)");
  }
}

void apply_overrides(spec::SceneDesc& scene, const RenderOverrides& o) {
  spec::RenderSettings& r = scene.render;
  if (o.integrator) r.integrator = *o.integrator;
  if (o.spp > 0) (r.integrator == spec::Integrator::Treemaker ? r.treemaker_spp : r.spp) = o.spp;
  if (o.width > 0) r.width = o.width;
  if (o.height > 0) r.height = o.height;
  if (o.seed) r.seed = *o.seed;
  if (o.time) {
    for (spec::TreeDesc& t : scene.trees) t.time = *o.time;
  }
  if (o.transparent) scene.output.transparent_sky = true;
  if (o.regularize) r.regularize = true;
  if (o.lod) r.lod = true;
}

std::vector<std::string> override_arguments(const RenderOverrides& o) {
  std::vector<std::string> args;
  const auto add = [&](const std::string& option, const std::string& value) {
    args.push_back(option);
    args.push_back(value);
  };
  if (o.width > 0) add("--width", std::to_string(o.width));
  if (o.height > 0) add("--height", std::to_string(o.height));
  if (o.spp > 0) add("--spp", std::to_string(o.spp));
  if (o.seed) add("--seed", std::to_string(*o.seed));
  if (o.time) {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, *o.time).ptr;  // shortest exact form
    add("--time", std::string(buf, end));
  }
  if (o.integrator) add("--integrator", spec::name_of(*o.integrator));
  if (o.transparent) args.push_back("--transparent");
  if (o.regularize) args.push_back("--regularize");
  if (o.lod) args.push_back("--lod");
  return args;
}

}  // namespace arbor::app
