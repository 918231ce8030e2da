// The scene file's keys of the image, the camera and the light: [render], [camera], [sun], [sky],
// [ground], [output], [animation] (scene_keys.h). The trees', meshes' and meadow's keys are in
// scene_keys_trees.cpp.
#include "formats/scene_keys.h"

#include <charconv>
#include <cstring>

namespace arbor::formats {

using keys::custom;
using keys::file;
using keys::flag;
using keys::value;

SceneKeyReader::SceneKeyReader(const std::string& path) : TomlReader(path) {
  const auto slash = path.find_last_of('/');
  if (slash != std::string::npos) folder_ = path.substr(0, slash + 1);
}

std::string SceneKeyReader::file(const toml::node& n, const std::string& name) const {
  const std::string v = text(n, name);
  if (v.empty()) fail(n, name + " must not be empty");
  const std::string resolved = v[0] == '/' ? v : folder_ + v;
  files_.push_back({resolved, at(n.source()), name});
  return resolved;
}

bool belongs_to(std::string_view models, std::string_view name) {
  while (!models.empty()) {
    const std::size_t space = models.find(' ');
    if (models.substr(0, space) == name) return true;
    if (space == std::string_view::npos) break;
    models = models.substr(space + 1);
  }
  return false;
}

std::string exact_number(double v) {
  char buf[32];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
std::string exact_triple(const spec::Vec3d& v) {
  return "[" + exact_number(v[0]) + ", " + exact_number(v[1]) + ", " + exact_number(v[2]) + "]";
}

namespace {

constexpr Range kPixels{1, 16384, "pixels"};
constexpr Range kSamples{1, 1 << 20, "samples per pixel"};
constexpr Range kAnySeed{0, 0x1p63, ""};
constexpr Range kWorld{-1e7, 1e7, "metres"};
constexpr Range kAzimuth{-360, 360, "degrees"};
constexpr Range kUnit{0, 1, ""};

}  // namespace

const std::vector<Key<spec::RenderSettings>>& render_keys() {
  using R = spec::RenderSettings;
  static const std::vector<Key<R>> table = {
      value("width", &R::width, kPixels, "the image's width"),
      value("height", &R::height, kPixels, "the image's height"),
      value("spp", &R::spp, kSamples,
            "samples per pixel of the path integrator (with noise_threshold: the most a pixel "
            "takes)"),
      value("seed", &R::seed, kAnySeed, "the seed of the sample sequence"),
      custom<R>(
          "integrator", KeyKind::Choice,
          "\"path\": exact light transport; \"treemaker\": TREE-MAKER's approximate "
          "shading (1990)",
          [](const KeyValue& v, R& r) { r.integrator = static_cast<spec::Integrator>(v.choice()); },
          [](const R& r) { return std::string(name_of(r.integrator)); })
          .of(choices_of(spec::kIntegratorNames))
          .shows("\"path\""),
      flag("regularize", &R::regularize,
           "roughen glossy coats after a diffuse bounce (pbrt-v4's rule; biased, off for "
           "references)")
          .only_for("path"),
      flag("lod", &R::lod,
           "thin distant trees' limbs and leaves by Weber & Penn's §5 (approximate, off for "
           "references)"),
      value("lod_quality", &R::lod_quality, Range{0.01, 100, ""},
            "Weber & Penn's quality factor: larger keeps detail farther away"),
      value("max_depth", &R::max_depth, Range{1, 1024, "bounces"}, "the most bounces a path takes"),
      value("treemaker_spp", &R::treemaker_spp, kSamples,
            "samples per pixel of the treemaker integrator (anti-aliasing)")
          .only_for("treemaker"),
      value("pass_spp", &R::pass_spp, kSamples,
            "samples a pixel takes per pass (a power of two keeps the sequence balanced)"),
      flag("independent_passes", &R::independent_passes,
           "each pass its own scramble, so the variance is unbiased (references)"),
      value("noise_threshold", &R::noise_threshold, kUnit,
            "adaptive sampling: the relative standard error a pixel stops at; 0: off")
          .only_for("path"),
      value("min_spp", &R::min_spp, Range{0, 1 << 20, "samples per pixel"},
            "adaptive sampling: the samples a pixel takes before it may stop")
          .only_for("path"),
      flag("aerial_perspective", &R::aerial_perspective,
           "the air between the camera and what it sees (the nishita and atmosphere skies, the "
           "path integrator)"),
  };
  return table;
}

const std::vector<Key<spec::CameraDesc>>& camera_keys() {
  using C = spec::CameraDesc;
  static const std::vector<Key<C>> table = {
      value("position", &C::position, kWorld, "the eye (z up)"),
      custom<C>("look_at", KeyKind::Triple, "the point the camera looks at",
                [](const KeyValue& v, C& c) {
                  c.look_at = v.triple();
                  c.look_at_where = v.where();
                })
          .within(kWorld)
          .shows("[0, 0, 6]"),
      custom<C>("up", KeyKind::Triple, "the direction that is up in the image",
                [](const KeyValue& v, C& c) {
                  c.up = v.triple();
                  c.up_where = v.where();
                })
          .within(kWorld)
          .shows("[0, 0, 1]"),
      custom<C>(
          "above_ground", KeyKind::Number,
          "with a [terrain]: the eye this many metres above the terrain under position's "
          "x and y (position's z is then ignored)",
          [](const KeyValue& v, C& c) {
            c.above_ground = v.number();
            c.above_ground_where = v.where();
          },
          [](const C& c) {
            return c.above_ground ? exact_number(*c.above_ground) : std::string("unset");
          })
          .within(Range{0, 1e5, "metres"})
          .shows("unset"),
      value("fov", &C::fov, Range{0.01, 179, "degrees"}, "the vertical field of view"),
      value("aperture_radius", &C::aperture_radius, Range{0, 100, "metres"},
            "the lens's radius for depth of field; 0: a pinhole, all in focus"),
      value("focus_distance", &C::focus_distance, Range{1e-4, 1e7, "metres"},
            "the distance in focus")
          .shows("the distance to look_at"),
      custom<C>("exposure", KeyKind::Number,
                "stops of exposure, or \"auto\": metered once per scene (docs/rendering.md, "
                "\"Exposure\")",
                [](const KeyValue& v, C& c) {
                  if (!v.node.is_string()) {
                    c.exposure = v.number();
                  } else if (v.text() == "auto") {
                    c.auto_exposure = true;
                  } else {
                    v.reader.fail(v.node, v.name + " must be a number of stops or \"auto\"");
                  }
                })
          .within(Range{-64, 64, "stops"})
          .shows("0"),
  };
  return table;
}

const std::vector<Key<spec::SunDesc>>& sun_keys() {
  using S = spec::SunDesc;
  static const std::vector<Key<S>> table = {
      flag("enabled", &S::enabled, "whether the sun shines (the sky still has its light)"),
      value("elevation", &S::elevation, Range{-90, 90, "degrees"}, "above the horizon"),
      value("azimuth", &S::azimuth, kAzimuth, "counter-clockwise from +x"),
      value("irradiance", &S::irradiance, Range{0, 1e6, ""},
            "scene-linear, on a plane facing the sun"),
      value("angular_diameter", &S::angular_diameter, Range{0.01, 30, "degrees"}, "the sun disk's"),
  };
  return table;
}

const std::vector<Key<spec::SkyDesc>>& sky_keys() {
  using S = spec::SkyDesc;
  static const std::vector<Key<S>> table = {
      custom<S>("model", KeyKind::Choice, "the sky's model (docs/rendering.md, \"Lights\")",
                [](const KeyValue& v, S& s) { s.model = static_cast<spec::SkyModel>(v.choice()); })
          .of(choices_of(spec::kSkyModelNames))
          .shows("\"preetham\""),
      custom<S>("turbidity", KeyKind::Number,
                "Preetham's turbidity; the atmosphere's: Linke's (at least 2.21, air without "
                "aerosols)",
                [](const KeyValue& v, S& s) {
                  s.turbidity = v.number();
                  s.turbidity_given = true;
                })
          .within(Range{1.7, 10, ""})
          .shows("3")
          .only_for("preetham atmosphere"),
      value("visibility", &S::visibility, Range{1, 300, "km"},
            "the aerosols by the meteorological range, instead of turbidity")
          .shows("unset")
          .only_for("atmosphere"),
      value("ground_albedo", &S::ground_albedo, kUnit,
            "the ground's albedo under the whole sky, for the light it sends back up")
          .shows("the luminance of [ground]'s albedo")
          .only_for("atmosphere"),
      value("air_density", &S::air_density, Range{0, 10, ""},
            "a multiplier of the standard atmosphere's air")
          .only_for("nishita atmosphere"),
      custom<S>("dust_density", KeyKind::Number,
                "a multiplier of the standard atmosphere's aerosols (the atmosphere: instead of "
                "turbidity)",
                [](const KeyValue& v, S& s) {
                  s.dust_density = v.number();
                  s.dust_given = true;
                })
          .within(Range{0, 100, ""})
          .shows("1")
          .only_for("nishita atmosphere"),
      value("ozone_density", &S::ozone_density, Range{0, 10, ""},
            "a multiplier of the standard atmosphere's ozone")
          .only_for("nishita atmosphere"),
      value("altitude", &S::altitude, Range{0, 50000, "metres"}, "the observer's, above the sea")
          .only_for("nishita atmosphere"),
      value("color", &S::color, Range{0, 1e6, ""}, "the radiance in every direction")
          .only_for("constant"),
      file("path", &S::path, "the environment map: a lat-long image OpenImageIO reads")
          .only_for("envmap"),
      value("rotation", &S::rotation, kAzimuth, "the map turned about z").only_for("envmap"),
      value("scale", &S::scale, Range{0, 1e6, ""}, "the map's radiance multiplied by")
          .only_for("envmap"),
  };
  return table;
}

const std::vector<Key<spec::GroundDesc>>& ground_keys() {
  using G = spec::GroundDesc;
  static const std::vector<Key<G>> table = {
      flag("enabled", &G::enabled, "whether the ground plane (z = 0) is there"),
      value("albedo", &G::albedo, kUnit, "the soil's albedo"),
      value("patch_albedo", &G::patch_albedo, kUnit, "the albedo of the noise patches"),
      value("patch_cover", &G::patch_cover, kUnit, "the share of the ground under patches"),
      value("patch_scale", &G::patch_scale, Range{0.01, 1e4, "metres"}, "a patch's size"),
      value("detail", &G::detail, kUnit, "the strength of the soil's finer scales"),
      value("stones", &G::stones, Range{0, 1000, "per square metre"}, "small stones on the soil"),
      value("stone_albedo", &G::stone_albedo, kUnit, "the stones' albedo"),
      value("litter", &G::litter, kUnit, "the share of the ground under leaf litter"),
      value("litter_albedo", &G::litter_albedo, kUnit, "the litter's albedo"),
  };
  return table;
}

namespace {

void check_extension(const KeyValue& v, const std::string& path, const char* ext) {
  const std::size_t len = std::strlen(ext);
  if (path.size() < len || path.compare(path.size() - len, len, ext) != 0)
    v.reader.fail(v.node, v.name + " must name a " + ext + " file, not \"" + path + "\"");
}

}  // namespace

const std::vector<Key<spec::OutputDesc>>& output_keys() {
  using O = spec::OutputDesc;
  static const std::vector<Key<O>> table = {
      custom<O>("exr", KeyKind::File,
                "the OpenEXR written (beauty, AOVs, variance); the command line's -o wins",
                [](const KeyValue& v, O& o) {
                  o.exr = v.file();
                  check_extension(v, o.exr, ".exr");
                })
          .shows("none"),
      custom<O>("png", KeyKind::File, "the display image written (sRGB through OCIO)",
                [](const KeyValue& v, O& o) {
                  o.png = v.file();
                  check_extension(v, o.png, ".png");
                })
          .shows("none"),
      custom<O>("colorspace", KeyKind::Text, "the EXR's colour space (an OCIO name)",
                [](const KeyValue& v, O& o) {
                  o.colorspace = v.text();
                  o.where.colorspace = v.where();
                })
          .shows("\"Linear Rec.709 (sRGB)\""),
      custom<O>("display", KeyKind::Text, "the PNG's OCIO display",
                [](const KeyValue& v, O& o) {
                  o.display = v.text();
                  o.where.display = v.where();
                })
          .shows("\"sRGB\""),
      custom<O>("view", KeyKind::Text, "the PNG's OCIO view",
                [](const KeyValue& v, O& o) {
                  o.view = v.text();
                  o.where.view = v.where();
                })
          .shows("\"ACES 1.0 SDR-video\""),
      value<O>("checkpoint_seconds", &O::checkpoint_seconds, Range{0, 1e7, "seconds"},
               "rewrite the outputs this often as passes finish; 0: never"),
      custom<O>("pixel_type", KeyKind::Choice, "the EXR's channels",
                [](const KeyValue& v, O& o) {
                  o.pixel_type = static_cast<imaging::PixelType>(v.choice());
                })
          .of(choices_of(imaging::kPixelTypeNames))
          .shows("\"half\""),
      flag<O>("transparent_sky", &O::transparent_sky,
              "camera rays that escape add nothing: alpha 0 there, for compositing"),
      custom<O>("aovs", KeyKind::List, "the extra layers of the EXR (docs/outputs.md)",
                [](const KeyValue& v, O& o) {
                  const toml::array* a = v.node.as_array();
                  if (!a) v.reader.fail(v.node, v.name + " must be an array of strings");
                  for (const toml::node& e : *a) {
                    const auto aov = static_cast<imaging::Aov>(
                        v.reader.choice_index(e, v.name, imaging::kAovNames));
                    o.aovs.add(aov);
                    if (aov == imaging::Aov::Treemaker)
                      o.treemaker_aov_where = v.reader.at(e.source());
                  }
                })
          .of(choices_of(imaging::kAovNames))
          .shows("[]"),
  };
  return table;
}

const std::vector<Key<spec::AnimationDesc>>& animation_keys() {
  using A = spec::AnimationDesc;
  static const std::vector<Key<A>> table = {
      value("frames", &A::frames, Range{1, 1000000, "frames"}, "how many frames (required)")
          .shows("required"),
      value("fps", &A::fps, Range{1e-3, 1000, "frames per second"},
            "frame N is rendered at N / fps seconds"),
      value("years_per_second", &A::years_per_second, Range{0, 1e4, ""},
            "years of growth per second, for growth models (the fractal model)"),
      flag("pin_seed", &A::pin_seed, "the same sample seed for every frame"),
  };
  return table;
}

}  // namespace arbor::formats
