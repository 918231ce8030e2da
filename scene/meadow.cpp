// Growing a meadow's tiles of grass blades and placing them (scene/meadow.h).
#include "scene/meadow.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/math.h"
#include "common/rng.h"
#include "scene/meadow_terrain.h"

namespace arbor::scene {

namespace {

constexpr double kBladesPerTuft = 12.0;
constexpr double kTuftRadius = 0.025;   // metres: σ of a tuft's blades about its centre
constexpr float kBelowGround = 0.005f;  // metres: blades start below the ground, no gap shows
constexpr double kSwayHz = 0.8;         // the blades' sway in the wind, cycles per second

// A standard normal variate (Box–Muller), clamped to ±3.
double normal(Rng& rng) {
  const double u = std::max(rng.uniform(), 1e-300);
  const double z = std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * rng.uniform());
  return std::clamp(z, -3.0, 3.0);
}

glm::vec3 to_vec3(const Rgb& c) {
  return glm::vec3(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
}

// One blade, rooted at `root`: the quadratic p(s) = root + L (s d₀ + s² c), s in [0, 1], exactly
// as a cubic Bézier; d₀ leans θ from upright towards azimuth φ, c bends it down by gravity and
// downwind; L makes its arc length the blade's length. Its width runs from `width` at the root
// to 2 % of it at the tip; its upper face looks up and back from the lean.
void add_blade(GrassTile& tile, glm::vec3 root, double length, double theta, double phi,
               double twist, double bend, glm::vec3 wind, double width, glm::vec3 color) {
  const glm::vec3 d0(static_cast<float>(std::sin(theta) * std::cos(phi)),
                     static_cast<float>(std::sin(theta) * std::sin(phi)),
                     static_cast<float>(std::cos(theta)));
  // Gravity's droop k, bounded so that the tip stays 1 cm above the root (with the arc's scale
  // about 1): s cosθ − s² k is concave, so no point between dips below the root or the tip.
  const double top = std::cos(theta) - std::max(0.1 * std::cos(theta), 0.01 / length);
  const double droop = std::min(bend * std::sin(theta), top);
  const glm::vec3 c = glm::vec3(0.0f, 0.0f, -static_cast<float>(droop)) + wind;
  double arc = 0.0;  // of s d₀ + s² c, by the midpoint rule
  for (int i = 0; i < 16; ++i) {
    const float s = (static_cast<float>(i) + 0.5f) / 16.0f;
    arc += glm::length(d0 + 2.0f * s * c) / 16.0;
  }
  const auto l = static_cast<float>(length / arc);
  const glm::vec3 a = l * d0, b = l * c;
  const glm::vec3 p[4] = {root, root + a / 3.0f, root + 2.0f * a / 3.0f + b / 3.0f, root + a + b};
  const auto w = static_cast<float>(0.5 * width);
  const float r[4] = {w, w, 0.6f * w, 0.02f * w};
  const glm::vec3 across(static_cast<float>(-std::sin(phi + twist)),
                         static_cast<float>(std::cos(phi + twist)), 0.0f);
  for (int i = 0; i < 4; ++i) {
    const float s = static_cast<float>(i) / 3.0f;
    const glm::vec3 tangent = d0 + 2.0f * s * c;
    tile.points.emplace_back(p[i], r[i]);
    tile.normals.push_back(glm::normalize(glm::cross(tangent, across)));
  }
  tile.colors.push_back(color);
}

// The placements of a meadow on the plane z = 0: every cell of the tile grid the area touches.
void place_on_plane(const spec::MeadowDesc& d, Meadow& m) {
  const double side = d.tile;
  const auto ix0 = static_cast<std::int64_t>(std::floor(d.area[0] / side));
  const auto iy0 = static_cast<std::int64_t>(std::floor(d.area[1] / side));
  const auto ix1 = static_cast<std::int64_t>(std::ceil(d.area[2] / side));
  const auto iy1 = static_cast<std::int64_t>(std::ceil(d.area[3] / side));
  const auto half = static_cast<float>(0.5 * side);
  for (std::int64_t iy = iy0; iy < iy1; ++iy) {
    for (std::int64_t ix = ix0; ix < ix1; ++ix) {
      const std::uint64_t h =
          derive_key(derive_key(d.seed ^ 0x3ead0e5u, static_cast<std::uint64_t>(ix)),
                     static_cast<std::uint64_t>(iy));
      GrassPlacement p;
      p.tile = static_cast<int>(h % static_cast<std::uint64_t>(d.tiles));
      if (m.tiles[static_cast<std::size_t>(p.tile)].blades() == 0) continue;
      const float turn = static_cast<float>((h >> 32) % 4u) * 0.5f * static_cast<float>(kPi);
      const glm::vec3 centre(static_cast<float>(static_cast<double>(ix) * side) + half,
                             static_cast<float>(static_cast<double>(iy) * side) + half, 0.0f);
      p.to_world = glm::translate(glm::mat4(1.0f), centre) *
                   glm::rotate(glm::mat4(1.0f), turn, glm::vec3(0, 0, 1)) *
                   glm::translate(glm::mat4(1.0f), glm::vec3(-half, -half, 0.0f));
      p.to_object = glm::inverse(p.to_world);
      m.placements.push_back(p);
    }
  }
}

}  // namespace

GrassTile grow_grass_tile(const spec::MeadowDesc& d, int k, double clock) {
  GrassTile tile;
  Rng rng(derive_key(d.seed, static_cast<std::uint64_t>(k)));
  const double side = d.tile, expected = d.density * side * side;
  // floor(expected) blades, one more with the fraction's probability: the mean is exact.
  auto count = static_cast<std::size_t>(expected);
  if (rng.uniform() < expected - static_cast<double>(count)) ++count;
  const std::size_t tufts =
      static_cast<std::size_t>(std::ceil(static_cast<double>(count) * d.clumping / kBladesPerTuft));
  std::vector<glm::dvec2> centres(tufts);
  for (glm::dvec2& c : centres) c = {side * rng.uniform(), side * rng.uniform()};
  const glm::vec3 dry_tint = to_vec3(d.dry_reflectance) / glm::max(to_vec3(d.reflectance), 1e-4f);
  const double wind_dir = d.wind_direction * kPi / 180.0;
  // The wind's bend: 0 in calm air, approaching 0.6 in a gale (a blade lies over, not flat).
  const double wind_bend = 0.6 * (1.0 - std::exp(-d.wind / 6.0));
  tile.points.reserve(4 * count);
  tile.normals.reserve(4 * count);
  tile.colors.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    glm::dvec2 at{side * rng.uniform(), side * rng.uniform()};
    double phi = 2.0 * kPi * rng.uniform();
    if (tufts > 0 && rng.uniform() < d.clumping) {
      // A tuft's blade: about its centre, leaning away from it (wrapped: the tile repeats).
      const glm::dvec2& c = centres[static_cast<std::size_t>(rng.uniform() * tufts)];
      const glm::dvec2 off{kTuftRadius * normal(rng), kTuftRadius * normal(rng)};
      at = {std::fmod(c.x + off.x + side, side), std::fmod(c.y + off.y + side, side)};
      phi = std::atan2(off.y, off.x) + 0.4 * normal(rng);
    }
    const double length = d.height * std::exp(d.height_spread * normal(rng));
    const double theta = std::min(80.0, d.lean * (0.25 + 1.5 * rng.uniform())) * kPi / 180.0;
    const double twist = 0.5 * normal(rng);
    const double sway = 1.0 + 0.3 * std::sin(2.0 * kPi * (kSwayHz * clock + rng.uniform()));
    const glm::vec3 wind = static_cast<float>(wind_bend * sway) *
                           glm::vec3(static_cast<float>(std::cos(wind_dir)),
                                     static_cast<float>(std::sin(wind_dir)), 0.0f);
    const bool dry = rng.uniform() < d.dry;
    const double width = d.width * (0.7 + 0.6 * rng.uniform());
    add_blade(tile, glm::vec3(static_cast<float>(at.x), static_cast<float>(at.y), -kBelowGround),
              length, theta, phi, twist, d.bend, wind, width, dry ? dry_tint : glm::vec3(1.0f));
  }
  return tile;
}

Meadow grow_meadow(const spec::MeadowDesc& d, double clock, const Terrain& terrain) {
  Meadow m;
  if (d.density <= 0.0) return m;
  for (int k = 0; k < d.tiles; ++k) m.tiles.push_back(grow_grass_tile(d, k, clock));
  if (!terrain.empty()) {
    m.tiles = cut_tiles(m.tiles, d.tile);
    place_on_terrain(d, terrain, m);
  } else {
    place_on_plane(d, m);
  }
  materials::LeafMaterial grass;
  grass.front = to_vec3(d.reflectance);
  grass.back = to_vec3(d.back_reflectance);
  grass.transmittance = to_vec3(d.transmittance);
  grass.variation.value = 0.2f;
  grass.variation.hue = 0.3f;
  m.grass = grass;
  return m;
}

std::size_t Meadow::placed_blades() const {
  std::size_t n = 0;
  for (const GrassPlacement& p : placements) n += tiles[static_cast<std::size_t>(p.tile)].blades();
  return n;
}

std::size_t Meadow::distinct_blades() const {
  std::size_t n = 0;
  for (const GrassTile& t : tiles) n += t.blades();
  return n;
}

std::size_t Meadow::bytes() const {
  std::size_t n = placements.size() * sizeof(GrassPlacement);
  for (const GrassTile& t : tiles) n += t.bytes();
  return n;
}

}  // namespace arbor::scene
