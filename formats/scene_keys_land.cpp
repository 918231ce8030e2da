// The scene file's keys of the landscape: [terrain] (scene_keys.h; docs/landscape.md).
#include "formats/scene_keys.h"

namespace arbor::formats {

using keys::custom;
using keys::value;

namespace {
constexpr Range kUnitAlbedo{0, 1, ""};
}  // namespace

const std::vector<Key<TerrainDesc>>& terrain_keys() {
  using T = TerrainDesc;
  static const std::vector<Key<T>> table = {
      custom<T>(
          "kind", KeyKind::Choice,
          "\"hills\": fractional Brownian motion; \"mountains\": ridged noise; \"image\": a "
          "digital elevation model",
          [](const KeyValue& v, T& t) { t.kind = static_cast<TerrainKind>(v.choice()); },
          [](const T& t) { return std::string(kTerrainKindNames[static_cast<int>(t.kind)]); })
          .of(choices_of(kTerrainKindNames))
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
      value("rock_slope", &T::rock_slope, Range{1, 89, "degrees"},
            "faces steeper than this are rock; soil on the 10° below"),
      value("rock_albedo", &T::rock_albedo, kUnitAlbedo, "the rock's albedo (lichen varies it)"),
      value("soil_albedo", &T::soil_albedo, kUnitAlbedo, "bare soil's albedo, below the rock"),
  };
  return table;
}

}  // namespace arbor::formats
