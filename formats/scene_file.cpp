// Scene file reader (TOML): every key of the contract read by its table (scene_keys.h), each
// value range-checked, unknown keys and keys of another model refused, all with file, line and
// column; then the rules across keys.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <toml++/toml.h>

#include "common/input_file.h"
#include "formats/scene_file.h"
#include "formats/scene_keys.h"
#include "formats/scene_meadow.h"

namespace arbor::formats {

namespace {

// Table `name` of a model chosen by its key `choice` (read first, into `chosen`), each other key
// read by `table` and refused when it belongs to another model than the chosen one.
template <class D, class E, std::size_t N>
void read_by_model(const KeyValue& v, const std::string& name, const char* choice,
                   const std::array<const char*, N>& names, E& chosen,
                   const std::vector<Key<D>>& table, D& d) {
  const toml::table& t = v.table();
  const std::string key = name + "." + choice;
  if (const toml::node* n = t.get(choice))
    chosen = static_cast<E>(v.reader.choice_index(*n, key, names));
  const ModelInUse model{key, names[static_cast<std::size_t>(chosen)]};
  read_keys(v.reader, t, name, "[" + name + "]", table, d, &model);
}

// The sky's keys by the model in use, and the atmosphere's rules across them.
void read_sky(const KeyValue& v, spec::SkyDesc& s) {
  const toml::table& t = v.table();
  read_by_model(v, "sky", "model", spec::kSkyModelNames, s.model, sky_keys(), s);
  if (s.model == spec::SkyModel::Atmosphere) {
    const toml::node* first = nullptr;  // the aerosols, given by one key (in the table's order)
    for (const char* key : {"dust_density", "turbidity", "visibility"}) {
      const toml::node* n = t.get(key);
      if (n && first)
        v.reader.fail(*n,
                      "give the aerosols once: one of sky.turbidity, sky.visibility and "
                      "sky.dust_density");
      if (n) first = n;
    }
    if (s.turbidity_given && s.turbidity < spec::kClearestLinkeTurbidity) {
      v.reader.fail(*t.get("turbidity"),
                    "sky.turbidity (Linke's) must be at least 2.21, the turbidity of "
                    "air without aerosols and 1.5 cm of water vapour");
    }
  }
  if (s.model == spec::SkyModel::Envmap && s.path.empty())
    throw InputError(v.where(), "sky.model = \"envmap\" needs sky.path (an image OIIO reads)");
}

// The render settings by the integrator in use (a key of the other integrator is an error).
void read_render(const KeyValue& v, spec::RenderSettings& r) {
  read_by_model(v, "render", "integrator", spec::kIntegratorNames, r.integrator, render_keys(), r);
}

void read_terrain(const KeyValue& v, spec::TerrainDesc& t) {
  const toml::table& table = v.table();
  t.enabled = true;
  t.where = v.reader.at(table.source());
  if (const toml::node* kind = table.get("kind"))
    t.kind = static_cast<spec::TerrainKind>(
        v.reader.choice_index(*kind, "terrain.kind", spec::kTerrainKindNames));
  const ModelInUse model{"terrain.kind", spec::kTerrainKindNames[static_cast<int>(t.kind)]};
  read_keys(v.reader, table, "terrain", "[terrain]", terrain_keys(), t, &model);
  if (t.kind == spec::TerrainKind::Image && t.path.empty())
    throw InputError(t.where,
                     "terrain.kind = \"image\" needs terrain.path (a 16-bit PNG or an EXR)");
  if (t.kind != spec::TerrainKind::Image && t.size / t.resolution > 32766) {
    v.reader.fail(table.get("resolution") ? *table.get("resolution") : v.node,
                  "terrain.size / terrain.resolution must be at most 32766 samples across (" +
                      short_number(std::ceil(t.size / t.resolution)) + " asked)");
  }
}

// Aerial perspective is the air of the nishita or atmosphere sky, seen by the path integrator.
void check_aerial(const TomlReader& r, const toml::node& n, const spec::SceneDesc& s) {
  if (s.sky.model != spec::SkyModel::Nishita && s.sky.model != spec::SkyModel::Atmosphere)
    r.fail(n,
           "render.aerial_perspective needs sky.model = \"atmosphere\" or \"nishita\" (the "
           "air it models)");
  if (s.render.integrator != spec::Integrator::Path)
    r.fail(n, "render.aerial_perspective needs render.integrator = \"path\"");
}

// A table read by its keys into the part of the scene `member` names.
template <class D>
void read_table(const KeyValue& v, const std::vector<Key<D>>& keys, D& d) {
  read_keys(v.reader, v.table(), v.name, "[" + v.name + "]", keys, d);
}

// [rocks]: its keys, and a size band that is not empty.
void read_rocks(const KeyValue& v, spec::SceneDesc& s) {
  s.rocks.enabled = true;
  s.rocks.where = v.reader.at(v.table().source());
  read_table(v, rocks_keys(), s.rocks);
  if (s.rocks.size_min > s.rocks.size_max) {
    throw InputError(s.rocks.where, "rocks.size_min " + short_number(s.rocks.size_min) +
                                        " exceeds rocks.size_max " +
                                        short_number(s.rocks.size_max));
  }
}

// Each table of an array of tables ([[tree]], …) read by `keys` into a new element of `list`,
// which `check` then checks across its keys.
template <class D, class Check>
void read_array(const KeyValue& v, const std::vector<Key<D>>& keys, std::vector<D>& list,
                Check check) {
  const toml::array* a = v.node.as_array();
  if (!a)
    v.reader.fail(v.node, "'" + v.name + "' must be an array of tables: write [[" + v.name + "]]");
  for (const toml::node& e : *a) {
    const toml::table& t = v.reader.table(e, v.name);
    D& d = list.emplace_back();
    d.where = v.reader.at(t.source());
    read_keys(v.reader, t, v.name, "[[" + v.name + "]]", keys, d);
    check(d);
  }
}

}  // namespace

const std::vector<Key<spec::SceneDesc>>& scene_keys() {
  using S = spec::SceneDesc;
  using keys::custom;
  static const std::vector<Key<S>> table = {
      custom<S>("render", KeyKind::Table, "the image and how it is sampled",
                [](const KeyValue& v, S& s) { read_render(v, s.render); }),
      custom<S>("camera", KeyKind::Table, "the camera (z up)",
                [](const KeyValue& v, S& s) { read_table(v, camera_keys(), s.camera); }),
      custom<S>("sun", KeyKind::Table, "the sun",
                [](const KeyValue& v, S& s) { read_table(v, sun_keys(), s.sun); }),
      custom<S>("sky", KeyKind::Table, "the sky; its keys by its model",
                [](const KeyValue& v, S& s) { read_sky(v, s.sky); }),
      custom<S>("ground", KeyKind::Table, "the ground plane's material",
                [](const KeyValue& v, S& s) { read_table(v, ground_keys(), s.ground); }),
      custom<S>("terrain", KeyKind::Table, "a height field the scene stands on (docs/landscape.md)",
                [](const KeyValue& v, S& s) { read_terrain(v, s.terrain); }),
      custom<S>("meadow", KeyKind::Table, "grass blades as geometry",
                [](const KeyValue& v, S& s) {
                  s.meadow.where = v.reader.at(v.table().source());
                  read_table(v, meadow_keys(), s.meadow);
                  check_meadow(s.meadow);
                }),
      custom<S>("tree", KeyKind::Table, "[[tree]]: one tree, as many as wanted",
                [](const KeyValue& v, S& s) {
                  read_array(v, tree_keys(), s.trees, [](const spec::TreeDesc& d) {
                    if (d.species.empty())
                      throw InputError(d.where, "[[tree]] needs a species (a species file)");
                  });
                }),
      custom<S>("forest", KeyKind::Table, "[[forest]]: trees of a species scattered over an area",
                [](const KeyValue& v, S& s) {
                  read_array(v, forest_keys(), s.forests, [](const spec::ForestDesc& d) {
                    if (d.species.empty())
                      throw InputError(d.where, "[[forest]] needs a species (a species file)");
                    if (d.variants > d.count)
                      throw InputError(d.where, "forest.variants must not exceed forest.count");
                  });
                }),
      custom<S>("community", KeyKind::Table,
                "plants of several species grown together (docs/landscape.md)",
                [](const KeyValue& v, S& s) {
                  s.community.enabled = true;
                  s.community.where = v.reader.at(v.table().source());
                  read_table(v, community_keys(), s.community);
                  if (s.community.species.empty())
                    throw InputError(s.community.where,
                                     "[community] needs [[community.species]] (at least one)");
                }),
      custom<S>("rocks", KeyKind::Table,
                "boulders and stones on rock faces and scree (docs/landscape.md)", read_rocks),
      custom<S>("mesh", KeyKind::Table, "[[mesh]]: a Wavefront OBJ placed in the scene",
                [](const KeyValue& v, S& s) {
                  read_array(v, mesh_keys(), s.meshes, [](const spec::MeshDesc& d) {
                    if (d.path.empty())
                      throw InputError(d.where, "[[mesh]] needs a path (an OBJ file)");
                  });
                }),
      custom<S>("output", KeyKind::Table, "the files written and their colour",
                [](const KeyValue& v, S& s) {
                  const SourceLocation where = v.reader.at(v.table().source());
                  s.output.where = {where, where, where};
                  read_table(v, output_keys(), s.output);
                }),
      custom<S>("animation", KeyKind::Table, "frames over time (docs/farm.md)",
                [](const KeyValue& v, S& s) {
                  s.animation.where = v.reader.at(v.table().source());
                  read_table(v, animation_keys(), s.animation);
                  if (s.animation.frames == 0)
                    throw InputError(s.animation.where,
                                     "[animation] needs frames (how many frames the animation "
                                     "has)");
                }),
  };
  return table;
}

spec::SceneDesc parse_scene(const std::string& text, const std::string& path) {
  const SceneKeyReader reader(path);
  const toml::table root = reader.parse(text);
  spec::SceneDesc s;
  s.path = path;
  const SourceLocation file{path, 0, 0};
  s.camera.look_at_where = s.camera.up_where = file;
  s.output.where = {file, file, file};
  // A look_at at the position is reported at look_at, else at position, else at the table.
  if (const toml::node* camera = root.get("camera"); camera && camera->as_table()) {
    const toml::table& c = *camera->as_table();
    s.camera.look_at_where = s.camera.up_where = reader.at(c.source());
    if (const toml::node* position = c.get("position"))
      s.camera.look_at_where = reader.at(position->source());
  }
  read_keys(reader, root, "", "", scene_keys(), s);
  if (s.meadow.density > 0.0 && s.terrain.enabled) {
    // On a terrain the meadow's tiles are the terrain's cells (scene/meadow.h).
    const toml::node* tile = root["meadow"]["tile"].node();
    if (tile) {
      throw InputError(reader.at(tile->source()),
                       "meadow.tile is the terrain's cell on a [terrain] (" +
                           short_number(terrain_spacing(s.terrain)) + " m); leave it out");
    }
    s.meadow.tile = terrain_spacing(s.terrain);
    check_meadow(s.meadow);
  }
  if (s.rocks.enabled && !s.rocks.area && !s.terrain.enabled) {
    throw InputError(s.rocks.where,
                     "[rocks] needs an area ([[x0, y0], [x1, y1]]) without a [terrain] to lie on");
  }
  if (s.camera.above_ground && !s.terrain.enabled) {
    throw InputError(s.camera.above_ground_where,
                     "camera.above_ground needs a [terrain] to stand on");
  }
  // A camera on the terrain has its height, and so its look and focus, once the terrain is built
  // (scene::placed_camera); its position's z is the reader's until then.
  if (!s.camera.above_ground) check_camera(s.camera);
  if (s.sky.ground_albedo < 0.0) s.sky.ground_albedo = mean_albedo(s.ground);
  if (s.render.aerial_perspective)
    check_aerial(reader, *root.at_path("render.aerial_perspective").node(), s);
  if (s.camera.focus_distance == 0.0 && !s.camera.above_ground) {
    const double dx = s.camera.look_at[0] - s.camera.position[0];
    const double dy = s.camera.look_at[1] - s.camera.position[1];
    const double dz = s.camera.look_at[2] - s.camera.position[2];
    s.camera.focus_distance = std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  s.files = reader.files();
  return s;
}

spec::SceneDesc load_scene(const std::string& path) {
  spec::SceneDesc scene = parse_scene(read_text_input(path, "scene", kMaxTomlBytes), path);
  // Each input is checked where the scene names it, before anything is read or grown.
  const std::vector<std::string> used = scene_inputs(scene);
  for (const spec::FileRef& f : scene.files) {
    if (std::find(used.begin(), used.end(), f.path) == used.end()) continue;
    const std::string problem = input_file_problem(f.path);
    if (!problem.empty()) throw InputError(f.where, f.key + " " + f.path + " " + problem);
  }
  return scene;
}

}  // namespace arbor::formats
