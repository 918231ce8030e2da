// The scene file's keys of the landscape: [terrain] (scene_keys.h; docs/landscape.md).
#include "common/range.h"
#include "formats/scene_keys.h"

namespace arbor::formats {

using keys::custom;
using keys::value;

namespace {
constexpr Range kUnitAlbedo{0, 1, ""};
}  // namespace

const std::vector<Key<spec::TerrainDesc>>& terrain_keys() {
  using T = spec::TerrainDesc;
  static const std::vector<Key<T>> table = {
      custom<T>(
          "kind", KeyKind::Choice,
          "\"hills\": fractional Brownian motion; \"mountains\": ridged noise; \"image\": a "
          "digital elevation model",
          [](const KeyValue& v, T& t) { t.kind = static_cast<spec::TerrainKind>(v.choice()); },
          [](const T& t) { return std::string(spec::kTerrainKindNames[static_cast<int>(t.kind)]); })
          .of(choices_of(spec::kTerrainKindNames))
          .shows("\"hills\""),
      value("size", &T::size, Range{10, 50000, "metres"},
            "the square's side, centred on the origin")
          .only_for("hills mountains"),
      value("relief", &T::relief, Range{0, 10000, "metres"},
            "from the lowest point to the highest"),
      value("seed", &T::seed, Range{0, 0x1p63, ""}, "the seed of the procedural model")
          .only_for("hills mountains"),
      value("resolution", &T::resolution, Range{0.1, 1000, "metres"},
            "the distance between height samples")
          .only_for("hills mountains"),
      custom<T>(
          "path", KeyKind::File,
          "the elevation image: a 16-bit PNG or an EXR (its first channel), north up",
          [](const KeyValue& v, T& t) {
            t.path = v.file();
            t.path_where = v.where();
          },
          [](const T& t) { return t.path.empty() ? std::string("none") : "\"" + t.path + "\""; })
          .only_for("image")
          .shows("none"),
      value("metres_per_pixel", &T::metres_per_pixel, Range{0.01, 10000, "metres"},
            "the image's pixel spacing")
          .only_for("image"),
      value("height_scale", &T::height_scale, Range{1e-6, 1e6, "metres"},
            "metres per unit of the image's value (a PNG's 0 to 65535 read as 0 to 1)")
          .only_for("image"),
      value("surround", &T::surround, Range{0, 20, ""},
            "how many sides the model continues beyond the square each way, coarser, to the "
            "horizon (0: none; the square's edges then fall to its lowest level)")
          .only_for("hills mountains"),
      value("rock_slope", &T::rock_slope, Range{1, 89, "degrees"},
            "faces steeper than this are rock; soil on the 10° below"),
      value("rock_albedo", &T::rock_albedo, kUnitAlbedo, "the rock's albedo (lichen varies it)"),
      value("soil_albedo", &T::soil_albedo, kUnitAlbedo, "bare soil's albedo, below the rock"),
  };
  return table;
}

const std::vector<Key<spec::CommunityDesc>>& community_keys() {
  using C = spec::CommunityDesc;
  static const std::vector<Key<C>> table = {
      value("area", &C::area, Range{}, "[[x0, y0], [x1, y1]]: the rectangle it grows in"),
      value("years", &C::years, Range{1, 2000, "years"}, "the years simulated"),
      value("seed", &C::seed, Range{0, 0x1p63, ""}, "the seed of the simulation and variants"),
      custom<C>(
          "species", KeyKind::Table, "[[community.species]]: the species, at least one",
          [](const KeyValue& v, C& c) {
            const toml::array* a = v.node.as_array();
            if (!a) {
              v.reader.fail(v.node,
                            "'community.species' must be an array of tables: write "
                            "[[community.species]]");
            }
            for (const toml::node& e : *a) {
              const toml::table& t = v.reader.table(e, v.name);
              spec::CommunitySpecies& s = c.species.emplace_back();
              s.where = v.reader.at(t.source());
              read_keys(v.reader, t, v.name, "[[community.species]]", community_species_keys(), s);
              if (s.species.empty())
                throw InputError(s.where, "[[community.species]] needs a species file");
              for (const auto& [lo, hi, name] :
                   {std::tuple{s.altitude_min, s.altitude_max, "altitude"},
                    std::tuple{s.moisture_min, s.moisture_max, "moisture"}})
                if (lo > hi)
                  throw InputError(s.where, std::string("[[community.species]] ") + name + "_min " +
                                                short_number(lo) + " exceeds " + name + "_max " +
                                                short_number(hi));
            }
          },
          [](const C& c) { return std::to_string(c.species.size()) + " species"; })
          .shows("none"),
  };
  return table;
}

const std::vector<Key<spec::RocksDesc>>& rocks_keys() {
  using R = spec::RocksDesc;
  static const std::vector<Key<R>> table = {
      value("density", &R::density, Range{0, 100, "per m²"},
            "rocks per m² where the ground is all rock; half that on the soil below it (scree), "
            "a twentieth elsewhere"),
      value("size_min", &R::size_min, Range{0.01, 100, "metres"}, "the smallest rock's diameter"),
      value("size_max", &R::size_max, Range{0.01, 100, "metres"}, "the largest rock's diameter"),
      value("exponent", &R::exponent, Range{1.01, 6, ""},
            "the sizes' power law: a size's density falls as size^-exponent"),
      value("buried", &R::buried, Range{0, 0.9, ""}, "the share of a rock's height below ground"),
      value("variants", &R::variants, Range{1, 64, "shapes"}, "distinct shapes, instanced"),
      value("seed", &R::seed, Range{0, 0x1p63, ""}, "the seed of the shapes and the placement"),
      custom<R>(
          "area", KeyKind::Area,
          "[[x0, y0], [x1, y1]]: the rectangle they lie in (needed without a [terrain])",
          [](const KeyValue& v, R& r) { r.area = v.area(); },
          [](const R& r) {
            if (!r.area) return std::string("the terrain's square");
            const std::array<double, 4>& a = *r.area;
            return "[[" + short_number(a[0]) + ", " + short_number(a[1]) + "], [" +
                   short_number(a[2]) + ", " + short_number(a[3]) + "]]";
          })
          .shows("the terrain's square"),
      value("albedo", &R::albedo, kUnitAlbedo, "the rock's albedo (lichen and noise vary it)"),
  };
  return table;
}

}  // namespace arbor::formats
