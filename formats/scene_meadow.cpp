// The scene file's [meadow] table: the rules across its keys (its keys: scene_keys_trees.cpp).
#include "formats/scene_meadow.h"

#include <cstdint>
#include <string>

#include "common/range.h"

namespace arbor::formats {

void check_meadow(const spec::MeadowDesc& m) {
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
