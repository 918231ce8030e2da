// Scene file reader (TOML): every key of the contract, each value range-checked, unknown keys
// rejected, all with file, line and column.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <toml++/toml.h>

#include "common/input_file.h"
#include "formats/toml_reader.h"

#include "formats/scene_desc.h"
#include "formats/scene_meadow.h"
#include "formats/species_file.h"

namespace arbor::formats {

namespace {

namespace look_range = generator::look_range;

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

class SceneReader : TomlReader {
 public:
  explicit SceneReader(const std::string& path) : TomlReader(path), folder_(folder_of(path)) {}

  SceneDesc read(const std::string& text) {
    const toml::table root = parse(text);
    SceneDesc s;
    s.path = path();
    files_.clear();
    const SourceLocation file{path(), 0, 0};
    s.camera.look_at_where = s.camera.up_where = file;
    s.output.where = {file, file, file};
    for (auto&& [key, node] : root) {
      const std::string k(key.str());
      if (k == "render")
        render(table(node, k), s.render);
      else if (k == "camera")
        camera(table(node, k), s.camera);
      else if (k == "sun")
        sun(table(node, k), s.sun);
      else if (k == "sky")
        sky(table(node, k), s.sky);
      else if (k == "ground")
        ground(table(node, k), s.ground);
      else if (k == "meadow")
        read_meadow(*this, table(node, k), s.meadow);
      else if (k == "tree")
        for_each_table(node, k, [&](const toml::table& t) { s.trees.push_back(tree(t)); });
      else if (k == "forest")
        for_each_table(node, k, [&](const toml::table& t) { s.forests.push_back(forest(t)); });
      else if (k == "mesh")
        for_each_table(node, k, [&](const toml::table& t) { s.meshes.push_back(mesh(t)); });
      else if (k == "output")
        output(table(node, k), s.output);
      else if (k == "animation")
        animation(table(node, k), s.animation);
      else
        throw InputError(at(key.source()), "unknown table or key '" + k + "'");
    }
    check_camera(s.camera);
    if (s.sky.ground_albedo < 0.0) s.sky.ground_albedo = mean_albedo(s.ground);
    if (s.render.aerial_perspective)
      check_aerial(*root.at_path("render.aerial_perspective").node(), s);
    if (s.camera.focus_distance == 0.0) {
      const double dx = s.camera.look_at[0] - s.camera.position[0];
      const double dy = s.camera.look_at[1] - s.camera.position[1];
      const double dz = s.camera.look_at[2] - s.camera.position[2];
      s.camera.focus_distance = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    s.files = files_;
    return s;
  }

 private:
  template <typename F>
  void for_each_table(const toml::node& n, const std::string& name, F&& f) const {
    const toml::array* a = n.as_array();
    if (!a) fail(n, "'" + name + "' must be an array of tables: write [[" + name + "]]");
    for (const toml::node& e : *a) f(table(e, name));
  }

  std::string file(const toml::node& n, const std::string& name) const {
    const std::string v = text(n, name);
    if (v.empty()) fail(n, name + " must not be empty");
    const std::string resolved = v[0] == '/' ? v : folder_ + v;
    files_.push_back({resolved, at(n.source()), name});
    return resolved;
  }
  [[noreturn]] void unknown(const toml::key& key, const std::string& table) const {
    throw InputError(at(key.source()),
                     "unknown key '" + std::string(key.str()) + "' in [" + table + "]");
  }

  void render(const toml::table& t, RenderSettings& r) const {
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "width")
        r.width = static_cast<int>(integer(n, "render.width", 1, 16384));
      else if (k == "height")
        r.height = static_cast<int>(integer(n, "render.height", 1, 16384));
      else if (k == "spp")
        r.spp = static_cast<int>(integer(n, "render.spp", 1, 1 << 20));
      else if (k == "seed")
        r.seed = static_cast<std::uint64_t>(integer(n, "render.seed", 0, INT64_MAX));
      else if (k == "integrator")
        r.integrator =
            static_cast<Integrator>(choice_index(n, "render.integrator", kIntegratorNames));
      else if (k == "regularize")
        r.regularize = boolean(n, "render.regularize");
      else if (k == "lod")
        r.lod = boolean(n, "render.lod");
      else if (k == "lod_quality")
        r.lod_quality = number(n, "render.lod_quality", 0.01, 100.0);
      else if (k == "max_depth")
        r.max_depth = static_cast<int>(integer(n, "render.max_depth", 1, 1024));
      else if (k == "treemaker_spp")
        r.treemaker_spp = static_cast<int>(integer(n, "render.treemaker_spp", 1, 1 << 20));
      else if (k == "pass_spp")
        r.pass_spp = static_cast<int>(integer(n, "render.pass_spp", 1, 1 << 20));
      else if (k == "independent_passes")
        r.independent_passes = boolean(n, "render.independent_passes");
      else if (k == "noise_threshold")
        r.noise_threshold = number(n, "render.noise_threshold", 0.0, 1.0);
      else if (k == "min_spp")
        r.min_spp = static_cast<int>(integer(n, "render.min_spp", 0, 1 << 20));
      else if (k == "aerial_perspective")
        r.aerial_perspective = boolean(n, "render.aerial_perspective");
      else
        unknown(key, "render");
    }
  }

  // Aerial perspective is the air of the nishita or atmosphere sky, seen by the path integrator.
  void check_aerial(const toml::node& n, const SceneDesc& s) const {
    if (s.sky.model != SkyModel::Nishita && s.sky.model != SkyModel::Atmosphere)
      fail(n,
           "render.aerial_perspective needs sky.model = \"atmosphere\" or \"nishita\" (the "
           "air it models)");
    if (s.render.integrator != Integrator::Path)
      fail(n, "render.aerial_perspective needs render.integrator = \"path\"");
  }

  void camera(const toml::table& t, CameraDesc& c) const {
    // A look_at at the position is reported at look_at, else at position, else at the table.
    c.look_at_where = c.up_where = at(t.source());
    if (const toml::node* position = t.get("position"); position && !t.get("look_at")) {
      c.look_at_where = at(position->source());
    }
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "position")
        c.position = triple(n, "camera.position", -1e7, 1e7);
      else if (k == "look_at") {
        c.look_at = triple(n, "camera.look_at", -1e7, 1e7);
        c.look_at_where = at(n.source());
      } else if (k == "up") {
        c.up = triple(n, "camera.up", -1e7, 1e7);
        c.up_where = at(n.source());
      } else if (k == "fov")
        c.fov = number(n, "camera.fov", 0.01, 179.0);
      else if (k == "aperture_radius")
        c.aperture_radius = number(n, "camera.aperture_radius", 0.0, 100.0);
      else if (k == "focus_distance")
        c.focus_distance = number(n, "camera.focus_distance", 1e-4, 1e7);
      else if (k == "exposure" && n.is_string()) {
        if (text(n, "camera.exposure") != "auto")
          fail(n, "camera.exposure must be a number of stops or \"auto\"");
        c.auto_exposure = true;
      } else if (k == "exposure")
        c.exposure = number(n, "camera.exposure", -64.0, 64.0);
      else
        unknown(key, "camera");
    }
  }

  void animation(const toml::table& t, AnimationDesc& a) const {
    a.where = at(t.source());
    bool has_frames = false;
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "frames") {
        a.frames = static_cast<int>(integer(n, "animation.frames", 1, 1000000));
        has_frames = true;
      } else if (k == "fps")
        a.fps = number(n, "animation.fps", 1e-3, 1000.0);
      else if (k == "years_per_second")
        a.years_per_second = number(n, "animation.years_per_second", 0.0, 1e4);
      else if (k == "pin_seed")
        a.pin_seed = boolean(n, "animation.pin_seed");
      else
        unknown(key, "animation");
    }
    if (!has_frames)
      throw InputError(a.where, "[animation] needs frames (how many frames the animation has)");
  }

  void sun(const toml::table& t, SunDesc& s) const {
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "enabled")
        s.enabled = boolean(n, "sun.enabled");
      else if (k == "elevation")
        s.elevation = number(n, "sun.elevation", -90.0, 90.0);
      else if (k == "azimuth")
        s.azimuth = number(n, "sun.azimuth", -360.0, 360.0);
      else if (k == "irradiance")
        s.irradiance = number(n, "sun.irradiance", 0.0, 1e6);
      else if (k == "angular_diameter")
        s.angular_diameter = number(n, "sun.angular_diameter", 0.01, 30.0);
      else
        unknown(key, "sun");
    }
  }

  void sky(const toml::table& t, SkyDesc& s) const {
    // Whether the model is "atmosphere", known after the loop (a table's keys come in any order).
    const toml::node* model = t.get("model");
    const bool atmosphere =
        model && model->as_string() && model->as_string()->get() == "atmosphere";
    bool visibility = false;
    const toml::node* aerosol_key = nullptr;  // the first of the three given
    auto atmosphere_only = [&](const toml::node& n) {
      if (!atmosphere) fail(n, "this key belongs to sky.model = \"atmosphere\"");
    };
    auto aerosol = [&](const toml::node& n, bool& given) {
      given = true;
      if (!atmosphere) return;
      if (aerosol_key)
        fail(n,
             "give the aerosols once: one of sky.turbidity, sky.visibility and "
             "sky.dust_density");
      aerosol_key = &n;
    };
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "model")
        s.model = static_cast<SkyModel>(choice_index(n, "sky.model", kSkyModelNames));
      else if (k == "turbidity") {
        s.turbidity = number(n, "sky.turbidity", 1.7, 10.0);
        aerosol(n, s.turbidity_given);
      } else if (k == "visibility") {
        atmosphere_only(n);
        s.visibility = number(n, "sky.visibility", 1.0, 300.0);
        aerosol(n, visibility);
      } else if (k == "ground_albedo") {
        atmosphere_only(n);
        s.ground_albedo = number(n, "sky.ground_albedo", 0.0, 1.0);
      } else if (k == "air_density")
        s.air_density = number(n, "sky.air_density", 0.0, 10.0);
      else if (k == "dust_density") {
        s.dust_density = number(n, "sky.dust_density", 0.0, 100.0);
        aerosol(n, s.dust_given);
      } else if (k == "ozone_density")
        s.ozone_density = number(n, "sky.ozone_density", 0.0, 10.0);
      else if (k == "altitude")
        s.altitude = number(n, "sky.altitude", 0.0, 50000.0);
      else if (k == "color")
        s.color = triple(n, "sky.color", 0.0, 1e6);
      else if (k == "path")
        s.path = file(n, "sky.path");
      else if (k == "rotation")
        s.rotation = number(n, "sky.rotation", -360.0, 360.0);
      else if (k == "scale")
        s.scale = number(n, "sky.scale", 0.0, 1e6);
      else
        unknown(key, "sky");
    }
    if (atmosphere && s.turbidity_given && s.turbidity < kClearestLinkeTurbidity) {
      fail(*t.get("turbidity"),
           "sky.turbidity (Linke's) must be at least 2.21, the turbidity of "
           "air without aerosols and 1.5 cm of water vapour");
    }
    if (s.model == SkyModel::Envmap && s.path.empty()) {
      throw InputError(at(t.source()),
                       "sky.model = \"envmap\" needs sky.path (an image OIIO reads)");
    }
  }

  void ground(const toml::table& t, GroundDesc& g) const {
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "enabled")
        g.enabled = boolean(n, "ground.enabled");
      else if (k == "albedo")
        g.albedo = triple(n, "ground.albedo", 0.0, 1.0);
      else if (k == "patch_albedo")
        g.patch_albedo = triple(n, "ground.patch_albedo", 0.0, 1.0);
      else if (k == "patch_cover")
        g.patch_cover = number(n, "ground.patch_cover", 0.0, 1.0);
      else if (k == "patch_scale")
        g.patch_scale = number(n, "ground.patch_scale", 0.01, 1e4);
      else if (k == "detail")
        g.detail = number(n, "ground.detail", 0.0, 1.0);
      else if (k == "stones")
        g.stones = number(n, "ground.stones", 0.0, 1000.0);
      else if (k == "stone_albedo")
        g.stone_albedo = triple(n, "ground.stone_albedo", 0.0, 1.0);
      else if (k == "litter")
        g.litter = number(n, "ground.litter", 0.0, 1.0);
      else if (k == "litter_albedo")
        g.litter_albedo = triple(n, "ground.litter_albedo", 0.0, 1.0);
      else
        unknown(key, "ground");
    }
  }

  void bark(const toml::table& t, BarkOverride& b, const std::string& owner) const {
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "albedo")
        b.albedo = triple(n, owner + ".bark.albedo", look_range::kColour);
      else if (k == "bump_map")
        b.bump_map = file(n, owner + ".bark.bump_map");
      else if (k == "bump_height")
        b.bump_height = number(n, owner + ".bark.bump_height", look_range::kBumpHeight);
      else if (k == "bump_tile")
        b.bump_tile = number(n, owner + ".bark.bump_tile", look_range::kBumpTile);
      else if (k == "roughness")
        b.roughness = number(n, owner + ".bark.roughness", look_range::kBarkRoughness);
      else if (k == "albedo_map")
        b.albedo_map = file(n, owner + ".bark.albedo_map");
      else
        unknown(key, owner + ".bark");
    }
  }

  void leaf(const toml::table& t, LeafOverride& l, const std::string& owner) const {
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "reflectance")
        l.reflectance = triple(n, owner + ".leaf.reflectance", look_range::kColour);
      else if (k == "back_reflectance")
        l.back_reflectance = triple(n, owner + ".leaf.back_reflectance", look_range::kColour);
      else if (k == "transmittance")
        l.transmittance = triple(n, owner + ".leaf.transmittance", look_range::kColour);
      else if (k == "albedo_map")
        l.albedo_map = file(n, owner + ".leaf.albedo_map");
      else if (k == "cuticle_ior")
        l.cuticle_ior = number(n, owner + ".leaf.cuticle_ior", look_range::kCuticleIor);
      else if (k == "cuticle_roughness")
        l.cuticle_roughness =
            number(n, owner + ".leaf.cuticle_roughness", look_range::kCuticleRoughness);
      else if (k == "variation" || k == "hue_variation")
        (k == "variation" ? l.variation : l.hue_variation) =
            number(n, owner + ".leaf." + k, look_range::kLeafVariation);
      else if (k == "crown_gradient")
        l.crown_gradient = number(n, owner + ".leaf.crown_gradient", look_range::kCrownGradient);
      else if (k == "veins")
        l.veins = number(n, owner + ".leaf.veins", look_range::kVeins);
      else if (k == "season")
        l.season = static_cast<generator::Season>(
            choice_index(n, owner + ".leaf.season", generator::kSeasonNames));
      else
        unknown(key, owner + ".leaf");
    }
  }

  void treemaker(const toml::table& t, TreemakerOverride& w, const std::string& owner) const {
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      const std::string name = owner + ".treemaker." + k;
      // The template language's own range for these weights (treemaker-format.md).
      if (k == "ambient")
        w.ambient = number(n, name, 0.0, 10.0);
      else if (k == "lambert")
        w.lambert = number(n, name, 0.0, 10.0);
      else if (k == "height")
        w.height = number(n, name, 0.0, 10.0);
      else if (k == "radius")
        w.radius = number(n, name, 0.0, 10.0);
      else if (k == "angle")
        w.angle = number(n, name, 0.0, 10.0);
      else
        unknown(key, owner + ".treemaker");
    }
  }

  void placement(const toml::node& n, const std::string& k, Placement& p,
                 const std::string& owner) const {
    if (k == "position")
      p.position = triple(n, owner + ".position", -1e7, 1e7);
    else if (k == "rotation")
      p.rotation = number(n, owner + ".rotation", -360.0, 360.0);
    else if (k == "scale")
      p.scale = number(n, owner + ".scale", 1e-6, 1e6);
  }

  TreeDesc tree(const toml::table& t) const {
    TreeDesc d;
    d.where = at(t.source());
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "species")
        d.species = file(n, "tree.species");
      else if (k == "seed")
        d.seed = static_cast<std::uint64_t>(integer(n, "tree.seed", 0, INT64_MAX));
      else if (k == "position" || k == "rotation" || k == "scale")
        placement(n, k, d.placement, "tree");
      else if (k == "time")
        d.time = number(n, "tree.time", -1e6, 1e6);
      else if (k == "bark")
        bark(table(n, "tree.bark"), d.bark, "tree");
      else if (k == "leaf")
        leaf(table(n, "tree.leaf"), d.leaf, "tree");
      else if (k == "treemaker")
        treemaker(table(n, "tree.treemaker"), d.treemaker, "tree");
      else
        unknown(key, "[tree]");
    }
    if (d.species.empty()) throw InputError(d.where, "[[tree]] needs a species (a species file)");
    return d;
  }

  ForestDesc forest(const toml::table& t) const {
    ForestDesc d;
    d.where = at(t.source());
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "species")
        d.species = file(n, "forest.species");
      else if (k == "count")
        d.count = static_cast<int>(integer(n, "forest.count", 1, 10000000));
      else if (k == "variants")
        d.variants = static_cast<int>(integer(n, "forest.variants", 1, 10000));
      else if (k == "seed")
        d.seed = static_cast<std::uint64_t>(integer(n, "forest.seed", 0, INT64_MAX));
      else if (k == "area") {
        d.area = area(n, "forest.area");
      } else if (k == "bark")
        bark(table(n, "forest.bark"), d.bark, "forest");
      else if (k == "leaf")
        leaf(table(n, "forest.leaf"), d.leaf, "forest");
      else if (k == "treemaker")
        treemaker(table(n, "forest.treemaker"), d.treemaker, "forest");
      else
        unknown(key, "[forest]");
    }
    if (d.species.empty()) throw InputError(d.where, "[[forest]] needs a species (a species file)");
    if (d.variants > d.count)
      throw InputError(d.where, "forest.variants must not exceed forest.count");
    return d;
  }

  MeshMaterialDesc mesh_material(const toml::table& t, const std::string& name) const {
    MeshMaterialDesc m;
    const std::string owner = "mesh.material." + name;
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "kind")
        m.kind = choice(n, owner + ".kind", {"bark", "leaf", "diffuse"});
      else if (k == "albedo")
        m.albedo = triple(n, owner + ".albedo", look_range::kColour);
      else if (k == "reflectance")
        m.reflectance = triple(n, owner + ".reflectance", look_range::kColour);
      else if (k == "back_reflectance")
        m.back_reflectance = triple(n, owner + ".back_reflectance", look_range::kColour);
      else if (k == "transmittance")
        m.transmittance = triple(n, owner + ".transmittance", look_range::kColour);
      else if (k == "cuticle_ior")
        m.cuticle_ior = number(n, owner + ".cuticle_ior", look_range::kCuticleIor);
      else if (k == "cuticle_roughness")
        m.cuticle_roughness =
            number(n, owner + ".cuticle_roughness", look_range::kCuticleRoughness);
      else
        unknown(key, owner);
    }
    if (m.kind == "leaf" &&
        !generator::leaf_conserves_energy(m.reflectance, m.back_reflectance, m.transmittance)) {
      throw InputError(at(t.source()), owner + ": " + generator::kLeafEnergyRule);
    }
    return m;
  }

  MeshDesc mesh(const toml::table& t) const {
    MeshDesc d;
    d.where = at(t.source());
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "path")
        d.path = file(n, "mesh.path");
      else if (k == "up")
        d.up = choice(n, "mesh.up", {"z", "y"});
      else if (k == "position" || k == "rotation" || k == "scale")
        placement(n, k, d.placement, "mesh");
      else if (k == "material") {
        for (auto&& [mkey, mnode] : table(n, "mesh.material")) {
          const std::string name(mkey.str());
          d.materials[name] = mesh_material(table(mnode, "mesh.material." + name), name);
        }
      } else
        unknown(key, "[mesh]");
    }
    if (d.path.empty()) throw InputError(d.where, "[[mesh]] needs a path (an OBJ file)");
    return d;
  }

  void extension(const toml::node& n, const std::string& path, const char* ext,
                 const char* name) const {
    const std::size_t len = std::strlen(ext);
    if (path.size() < len || path.compare(path.size() - len, len, ext) != 0) {
      fail(n, std::string(name) + " must name a " + ext + " file, not \"" + path + "\"");
    }
  }

  void output(const toml::table& t, OutputDesc& o) const {
    o.where = {at(t.source()), at(t.source()), at(t.source())};
    for (auto&& [key, n] : t) {
      const std::string k(key.str());
      if (k == "exr") {
        o.exr = file(n, "output.exr");
        extension(n, o.exr, ".exr", "output.exr");
      } else if (k == "png") {
        o.png = file(n, "output.png");
        extension(n, o.png, ".png", "output.png");
      } else if (k == "colorspace") {
        o.colorspace = text(n, "output.colorspace");
        o.where.colorspace = at(n.source());
      } else if (k == "display") {
        o.display = text(n, "output.display");
        o.where.display = at(n.source());
      } else if (k == "view") {
        o.view = text(n, "output.view");
        o.where.view = at(n.source());
      } else if (k == "checkpoint_seconds")
        o.checkpoint_seconds = number(n, "output.checkpoint_seconds", 0.0, 1e7);
      else if (k == "pixel_type")
        o.pixel_type = static_cast<imaging::PixelType>(
            choice_index(n, "output.pixel_type", imaging::kPixelTypeNames));
      else if (k == "transparent_sky")
        o.transparent_sky = boolean(n, "output.transparent_sky");
      else if (k == "aovs") {
        const toml::array* a = n.as_array();
        if (!a) fail(n, "output.aovs must be an array of strings");
        for (const toml::node& e : *a) {
          const imaging::Aov aov =
              static_cast<imaging::Aov>(choice_index(e, "output.aovs", imaging::kAovNames));
          o.aovs.add(aov);
          if (aov == imaging::Aov::Treemaker) o.treemaker_aov_where = at(e.source());
        }
      } else
        unknown(key, "output");
    }
  }

  std::string folder_;
  mutable std::vector<FileRef> files_;  // filled by file() as the keys are read
};

}  // namespace

SceneDesc parse_scene(const std::string& text, const std::string& path) {
  return SceneReader(path).read(text);
}

SceneDesc load_scene(const std::string& path) {
  SceneDesc scene = parse_scene(read_text_input(path, "scene", kMaxTomlBytes), path);
  // Each input is checked where the scene names it, before anything is read or grown.
  const std::vector<std::string> used = scene_inputs(scene);
  for (const FileRef& f : scene.files) {
    if (std::find(used.begin(), used.end(), f.path) == used.end()) continue;
    const std::string problem = input_file_problem(f.path);
    if (!problem.empty()) throw InputError(f.where, f.key + " " + f.path + " " + problem);
  }
  return scene;
}

}  // namespace arbor::formats
