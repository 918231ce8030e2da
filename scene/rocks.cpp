// Rocks: shapes from a displaced icosphere, placed by rejection on the terrain's cover.
#include "scene/rocks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/error.h"
#include "common/math.h"
#include "common/rng.h"
#include "materials/bark_noise.h"

namespace arbor::scene {

namespace {

constexpr std::uint64_t kMostRocks = 10'000'000;
constexpr double kSteepestRest = 45.0;  // degrees: about the angle of repose of coarse scree

// The unit icosphere subdivided `levels` times (each triangle into four, new points pushed out
// to the sphere): 10·4^levels + 2 vertices.
void icosphere(int levels, std::vector<glm::vec3>& v, std::vector<std::uint32_t>& f) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (glm::vec3& p : v) p = glm::normalize(p);
  f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
       4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
       6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      const auto id = static_cast<std::uint32_t>(v.size() - 1);
      middle.emplace(key, id);
      return id;
    };
    std::vector<std::uint32_t> next;
    next.reserve(f.size() * 4);
    for (std::size_t k = 0; k < f.size(); k += 3) {
      const std::uint32_t a = f[k], b = f[k + 1], c = f[k + 2];
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f.swap(next);
  }
}

// One boulder: the sphere's radius displaced by three octaves of noise, a few flat cuts (the
// faces a rock breaks along), squashed to a random height and width.
RockShape make_shape(std::uint64_t key) {
  Rng rng(key);
  RockShape s;
  icosphere(3, s.positions, s.indices);
  const double ox = 100.0 * rng.uniform(), oy = 100.0 * rng.uniform(), oz = 100.0 * rng.uniform();
  const glm::vec3 squash(static_cast<float>(rng.vary(1.0, 0.15)),
                         static_cast<float>(rng.vary(0.8, 0.15)),
                         static_cast<float>(rng.vary(0.6, 0.15)));
  std::array<glm::vec4, 5> cuts;  // planes n·p = d: nothing of the rock lies beyond them
  for (glm::vec4& c : cuts) {
    const double z = rng.symmetric(), phi = 2.0 * kPi * rng.uniform();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    c = glm::vec4(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                  static_cast<float>(z), static_cast<float>(rng.vary(0.8, 0.1)));
  }
  for (glm::vec3& p : s.positions) {
    double r = 1.0;
    for (int o = 0; o < 3; ++o) {
      const double f = 1.5 * std::pow(2.0, o);
      r += 0.22 / std::pow(2.0, o) *
           materials::gradient_noise(ox + f * p.x, oy + f * p.y, oz + f * p.z);
    }
    glm::vec3 q = p * static_cast<float>(r);
    for (const glm::vec4& c : cuts) {
      const glm::vec3 n(c);
      const float beyond = glm::dot(n, q) - c.w;
      if (beyond > 0.0f) q -= 0.9f * beyond * n;
    }
    p = q * squash;
  }
  // Smooth normals: the area-weighted face normals about each vertex.
  s.normals.assign(s.positions.size(), glm::vec3(0.0f));
  for (std::size_t k = 0; k < s.indices.size(); k += 3) {
    const glm::vec3 &a = s.positions[s.indices[k]], &b = s.positions[s.indices[k + 1]],
                    &c = s.positions[s.indices[k + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    for (int i = 0; i < 3; ++i) s.normals[s.indices[k + static_cast<std::size_t>(i)]] += n;
  }
  for (glm::vec3& n : s.normals) n = glm::normalize(n);
  s.bottom = s.top = s.positions.front().z;
  s.reach = 0.0f;
  for (const glm::vec3& p : s.positions) {
    s.bottom = std::min(s.bottom, p.z);
    s.top = std::max(s.top, p.z);
    s.reach = std::max(s.reach, std::hypot(p.x, p.y));
  }
  return s;
}

// How far the ground lies below the plane through `centre` across `n` (negative: below) at its
// lowest under a footprint of radius r in that plane, measured along n: at 32 points on its rim
// and on a grid inside it finer than half the terrain's spacing (the surface is piecewise linear,
// so its lowest point over the disk is on the rim or at a vertex inside).
double lowest_ground(const Terrain& t, glm::dvec3 centre, glm::dvec3 n, double r) {
  const glm::dvec3 u = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                                                          : glm::cross(n, glm::dvec3(0, 1, 0)));
  const glm::dvec3 v = glm::cross(n, u);
  double low = 0.0;
  auto at = [&](double a, double b) {
    const glm::dvec3 q = centre + a * u + b * v;
    low = std::min(low, (t.height(q.x, q.y) - q.z) * n.z);
  };
  for (int k = 0; k < 32; ++k) {
    const double a = 2.0 * kPi * k / 32.0;
    at(r * std::cos(a), r * std::sin(a));
  }
  const double step = std::min(0.25 * r, t.empty() ? r : 0.4 * t.spacing());
  for (double a = -r; a <= r; a += step)
    for (double b = -r; b <= r; b += step)
      if (a * a + b * b <= r * r) at(a, b);
  return low;
}

// The turn that takes z to n (about the axis z × n), as a matrix.
glm::mat4 tilt_to(glm::vec3 n) {
  const glm::vec3 axis = glm::cross(glm::vec3(0, 0, 1), n);
  const float s = glm::length(axis);
  if (s < 1e-6f) return glm::mat4(1.0f);
  return glm::rotate(glm::mat4(1.0f), std::atan2(s, n.z), axis / s);
}

}  // namespace

std::size_t Rocks::bytes() const {
  std::size_t b = placements.size() * sizeof(RockPlacement);
  for (const RockShape& s : shapes) b += s.bytes();
  return b;
}

double rock_share(glm::vec2 cover) {
  return std::max({static_cast<double>(cover.y), 0.5 * cover.x, 0.05});
}

double power_law_size(double lo, double hi, double exponent, double u) {
  const double e = 1.0 - exponent;  // exponent > 1: e < 0
  const double a = std::pow(lo, e), b = std::pow(hi, e);
  return std::pow(a + u * (b - a), 1.0 / e);
}

Rocks place_rocks(const spec::RocksDesc& d, const Terrain& terrain) {
  Rocks rocks;
  materials::GroundMaterial rock;  // all rock: the terrain's lichen-spotted rock
  rock.terrain = true;
  rock.rock_albedo = glm::vec3(d.albedo[0], d.albedo[1], d.albedo[2]);
  rocks.material = rock;
  if (d.density <= 0.0) return rocks;
  std::array<double, 4> area{};
  if (d.area) {
    area = *d.area;
  } else {
    const glm::dvec2 o = terrain.origin(), e = terrain.extent();
    area = {o.x, o.y, o.x + e.x, o.y + e.y};
  }
  const double w = area[2] - area[0], h = area[3] - area[1];
  const double expected = d.density * w * h;  // candidates; each kept by its ground's share
  if (expected > static_cast<double>(kMostRocks)) {
    throw InputError(d.where, "[rocks] would place up to " +
                                  std::to_string(static_cast<long long>(expected)) +
                                  " rocks (at most 10,000,000); lower its density or its area");
  }
  for (int v = 0; v < d.variants; ++v)
    rocks.shapes.push_back(make_shape(derive_key(d.seed ^ 0x70c5u, static_cast<std::uint64_t>(v))));
  Rng rng(derive_key(d.seed ^ 0x5c4eeu, 1));
  auto count = static_cast<std::uint64_t>(expected);
  if (rng.uniform() < expected - static_cast<double>(count)) ++count;
  for (std::uint64_t i = 0; i < count; ++i) {
    Rng r(derive_key(d.seed ^ 0x5c4eeu, i + 2));
    const double x = area[0] + w * r.uniform(), y = area[1] + h * r.uniform();
    const double share = terrain.empty() ? 1.0 : rock_share(terrain.cover(x, y));
    if (r.uniform() >= share) continue;
    // A rock rests on slopes up to kSteepestRest; steeper faces shed theirs to the scree below.
    if (!terrain.empty() && terrain.slope(x, y) > kSteepestRest) continue;
    RockPlacement p;
    p.shape = static_cast<int>(r.uniform() * d.variants);
    const RockShape& s = rocks.shapes[static_cast<std::size_t>(p.shape)];
    p.diameter =
        static_cast<float>(power_law_size(d.size_min, d.size_max, d.exponent, r.uniform()));
    const double scale = 0.5 * p.diameter;
    p.ground = static_cast<float>(terrain.height(x, y));
    // Resting on the slope: its axis the ground's normal, sunk along it so that `buried` of its
    // height is below the lowest ground under its footprint.
    const glm::vec3 up = terrain.normal(x, y);
    const glm::dvec3 centre(x, y, p.ground);
    const double low = lowest_ground(terrain, centre, glm::dvec3(up), scale * s.reach);
    const double height = scale * (s.top - s.bottom);
    // Ground rougher than 0.4 of its height under it (a crest, a gully): it would not rest.
    if (low < -0.4 * height) continue;
    const glm::dvec3 at = centre + glm::dvec3(up) * (low - d.buried * height - scale * s.bottom);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(at)) * tilt_to(up);
    m = glm::rotate(m, static_cast<float>(2.0 * kPi * r.uniform()), glm::vec3(0, 0, 1));
    p.to_world = glm::scale(m, glm::vec3(static_cast<float>(scale)));
    p.to_object = glm::inverse(p.to_world);
    rocks.placements.push_back(p);
  }
  return rocks;
}

}  // namespace arbor::scene
