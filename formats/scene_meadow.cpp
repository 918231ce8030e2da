// The scene file's [meadow] table.
#include "formats/scene_meadow.h"

#include <cstdint>
#include <string>

#include "common/range.h"

namespace arbor::formats {

void read_meadow(const TomlReader& r, const toml::table& t, MeadowDesc& m) {
  m.where = r.at(t.source());
  for (auto&& [key, n] : t) {
    const std::string k(key.str());
    const std::string name = "meadow." + k;
    if (k == "density")
      m.density = r.number(n, name, 0.0, 50000.0);
    else if (k == "area")
      m.area = r.area(n, name);
    else if (k == "height")
      m.height = r.number(n, name, 0.01, 3.0);
    else if (k == "height_spread")
      m.height_spread = r.number(n, name, 0.0, 1.0);
    else if (k == "width")
      m.width = r.number(n, name, 0.0005, 0.05);
    else if (k == "clumping")
      m.clumping = r.number(n, name, 0.0, 1.0);
    else if (k == "lean")
      m.lean = r.number(n, name, 0.0, 80.0);
    else if (k == "bend")
      m.bend = r.number(n, name, 0.0, 1.0);
    else if (k == "dry")
      m.dry = r.number(n, name, 0.0, 1.0);
    else if (k == "wind")
      m.wind = r.number(n, name, 0.0, 30.0);
    else if (k == "wind_direction")
      m.wind_direction = r.number(n, name, -360.0, 360.0);
    else if (k == "tile")
      m.tile = r.number(n, name, 0.1, 10.0);
    else if (k == "tiles")
      m.tiles = static_cast<int>(r.integer(n, name, 1, 64));
    else if (k == "seed")
      m.seed = static_cast<std::uint64_t>(r.integer(n, name, 0, INT64_MAX));
    else if (k == "reflectance")
      m.reflectance = r.triple(n, name, 0.0, 1.0);
    else if (k == "back_reflectance")
      m.back_reflectance = r.triple(n, name, 0.0, 1.0);
    else if (k == "transmittance")
      m.transmittance = r.triple(n, name, 0.0, 1.0);
    else if (k == "dry_reflectance")
      m.dry_reflectance = r.triple(n, name, 0.0, 1.0);
    else
      throw InputError(r.at(key.source()), "unknown key '" + k + "' in [meadow]");
  }
  for (int c = 0; c < 3; ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (m.reflectance[i] + m.transmittance[i] > 1.0 ||
        m.back_reflectance[i] + m.transmittance[i] > 1.0) {
      throw InputError(m.where,
                       "[meadow] reflectance + transmittance exceeds 1 in a channel: a blade "
                       "would create light");
    }
  }
  // Bounded so that a scene cannot ask for more blades than memory holds: 10⁹ placed blades.
  const double area = (m.area[2] - m.area[0]) * (m.area[3] - m.area[1]);
  if (m.density * area > 1e9) {
    throw InputError(m.where, "[meadow] density × area is " + short_number(m.density * area) +
                                  " blades, more than the 10⁹ arbor places");
  }
  const double cells = meadow_cells(m);
  if (m.density > 0.0 && cells > 1e6) {
    throw InputError(m.where, "[meadow] area holds " + short_number(cells) +
                                  " tiles, more than 10⁶: make meadow.tile larger");
  }
  if (m.density * m.tile * m.tile * m.tiles > 2e7) {
    throw InputError(m.where,
                     "[meadow] density × tile² × tiles is more than 2·10⁷ distinct blades");
  }
}

}  // namespace arbor::formats
