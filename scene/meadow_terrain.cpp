// A meadow on a terrain (scene/meadow.h, grow_meadow): the tiles cut into the cells' two
// triangles, each half sheared onto the triangle it is placed on, thinned by the ground's cover.
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "common/math.h"
#include "common/rng.h"
#include "scene/meadow_terrain.h"

namespace arbor::scene {

namespace {

// The densities a half-cell is kept at, as shares of its blades.
constexpr std::array<double, 4> kKeep{1.0, 0.5, 0.25, 0.125};

// The blades of `tile` (side `side`) whose roots are in one triangle of the cell — the lower
// (x + y < side: Embree's (v0, v1, v3)) or the upper — the first ⌈keep × n⌉ of them.
GrassTile half_tile(const GrassTile& tile, double side, int upper, double keep) {
  std::vector<std::size_t> in;
  for (std::size_t b = 0; b < tile.blades(); ++b) {
    const glm::vec4& root = tile.points[GrassTile::kPointsPerBlade * b];
    if ((static_cast<double>(root.x) + static_cast<double>(root.y) >= side) == (upper != 0))
      in.push_back(b);
  }
  in.resize(static_cast<std::size_t>(std::ceil(keep * static_cast<double>(in.size()))));
  GrassTile half;
  for (const std::size_t b : in) {
    for (int k = 0; k < GrassTile::kPointsPerBlade; ++k) {
      half.points.push_back(tile.points[GrassTile::kPointsPerBlade * b + k]);
      half.normals.push_back(tile.normals[GrassTile::kPointsPerBlade * b + k]);
    }
    half.colors.push_back(tile.colors[b]);
  }
  return half;
}

// The level of kKeep a half-cell of share `f` takes (kKeep.size(): none), by the uniform `u`:
// between the two levels about f, with the probabilities that make the mean share f.
std::size_t level_for(double f, double u) {
  for (std::size_t l = 0; l + 1 < kKeep.size(); ++l) {
    if (f >= kKeep[l + 1]) return u * (kKeep[l] - kKeep[l + 1]) < f - kKeep[l + 1] ? l : l + 1;
  }
  return u * kKeep.back() < f ? kKeep.size() - 1 : kKeep.size();
}

}  // namespace

double grass_share(glm::vec2 cover) {
  return (1.0 - static_cast<double>(cover.y)) * (1.0 - 0.7 * static_cast<double>(cover.x));
}

double triangle_grass_share(const Terrain& terrain, int i, int j, int upper) {
  // The centroid and the points ⅔ of the way from it to each corner, in the cell's units.
  const double c = upper ? 2.0 / 3.0 : 1.0 / 3.0;
  const glm::dvec2 corners[3] = {upper ? glm::dvec2(1, 1) : glm::dvec2(0, 0), {1, 0}, {0, 1}};
  const double s = terrain.spacing();
  const glm::dvec2 o = terrain.origin() + s * glm::dvec2(i, j);
  double f = grass_share(terrain.cover(o.x + c * s, o.y + c * s));
  for (const glm::dvec2& v : corners) {
    const glm::dvec2 p = glm::dvec2(c) + (2.0 / 3.0) * (v - glm::dvec2(c));
    f = std::min(f, grass_share(terrain.cover(o.x + p.x * s, o.y + p.y * s)));
  }
  return f;
}

void place_on_terrain(const spec::MeadowDesc& d, const Terrain& terrain, Meadow& m) {
  const double s = terrain.spacing();
  const glm::dvec2 o = terrain.origin();
  const int i0 = std::max(0, static_cast<int>(std::floor((d.area[0] - o.x) / s)));
  const int j0 = std::max(0, static_cast<int>(std::floor((d.area[1] - o.y) / s)));
  const int i1 =
      std::min(terrain.columns() - 1, static_cast<int>(std::ceil((d.area[2] - o.x) / s)));
  const int j1 = std::min(terrain.rows() - 1, static_cast<int>(std::ceil((d.area[3] - o.y) / s)));
  const auto levels = static_cast<std::uint64_t>(kKeep.size());
  // The turn by 180° about the cell's centre: it takes one half onto the other.
  const glm::dmat4 turn = glm::translate(glm::dmat4(1.0), glm::dvec3(s, s, 0.0)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, -1.0, 1.0));
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      const double h0 = terrain.at(i, j), h1 = terrain.at(i + 1, j);
      const double h2 = terrain.at(i + 1, j + 1), h3 = terrain.at(i, j + 1);
      for (int upper = 0; upper < 2; ++upper) {
        const std::uint64_t h =
            derive_key(derive_key(derive_key(d.seed ^ 0x7e3ad0u, static_cast<std::uint64_t>(i)),
                                  static_cast<std::uint64_t>(j)),
                       static_cast<std::uint64_t>(upper));
        const double f = triangle_grass_share(terrain, i, j, upper);
        const std::size_t level = level_for(f, static_cast<double>(h >> 40) / double(1 << 24));
        if (level == kKeep.size()) continue;
        const std::uint64_t k = h % static_cast<std::uint64_t>(d.tiles);
        const std::uint64_t from = (h >> 20) & 1u;  // the tile's half placed here
        GrassPlacement p;
        p.tile = static_cast<int>((k * 2 + from) * levels + level);
        if (m.tiles[static_cast<std::size_t>(p.tile)].blades() == 0) continue;
        // The triangle's plane z = c + a·x + b·y in the cell's frame (x, y from its corner).
        const double a = upper ? (h2 - h3) / s : (h1 - h0) / s;
        const double b = upper ? (h2 - h1) / s : (h3 - h0) / s;
        const double c = upper ? h1 + h3 - h2 : h0;
        glm::dmat4 shear(1.0);
        shear[0][2] = a;
        shear[1][2] = b;
        shear[3][2] = c;
        const glm::dmat4 world =
            glm::translate(glm::dmat4(1.0), glm::dvec3(o.x + i * s, o.y + j * s, 0.0)) * shear *
            (from != static_cast<std::uint64_t>(upper) ? turn : glm::dmat4(1.0));
        p.to_world = glm::mat4(world);
        p.to_object = glm::mat4(glm::inverse(world));
        p.sheared = true;
        m.placements.push_back(p);
      }
    }
  }
}

std::vector<GrassTile> cut_tiles(const std::vector<GrassTile>& whole, double side) {
  std::vector<GrassTile> cut;
  for (const GrassTile& t : whole) {
    for (int upper = 0; upper < 2; ++upper) {
      for (const double keep : kKeep) cut.push_back(half_tile(t, side, upper, keep));
    }
  }
  return cut;
}

}  // namespace arbor::scene
