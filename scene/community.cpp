// The plant community's simulation (scene/community.h).
#include "scene/community.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <array>
#include <cstdint>

#include "common/error.h"
#include "common/math.h"
#include "common/range.h"
#include "common/rng.h"

namespace arbor::scene {

namespace {

constexpr std::size_t kMostAlive = 4'000'000;

// 0 outside [lo, hi], rising to 1 over `soft` inside it (over half the band if it is narrower):
// a plant never stands outside its stated band.
double band(double v, double lo, double hi, double soft) {
  if (!(v >= lo && v <= hi)) return 0.0;
  soft = std::min(soft, 0.5 * (hi - lo));
  if (soft <= 0.0) return 1.0;
  return std::min({1.0, (v - lo) / soft, (hi - v) / soft});
}

// Plants on a grid of cells of side `cell` over the community's area, for the neighbours of a
// circle: each cell's plants stored together (position and radius beside the index), so a search
// reads memory in order.
class Grid {
 public:
  struct Entry {
    double x, y, radius;
    std::size_t index;
  };
  Grid(const std::vector<Plant>& plants, const std::array<double, 4>& area, double cell)
      : x0_(area[0]), y0_(area[1]), cell_(cell) {
    nx_ = static_cast<std::int64_t>(std::floor((area[2] - area[0]) / cell)) + 1;
    ny_ = static_cast<std::int64_t>(std::floor((area[3] - area[1]) / cell)) + 1;
    start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
    std::vector<std::size_t> of(plants.size());
    for (std::size_t i = 0; i < plants.size(); ++i) {
      of[i] = cell_of(plants[i].position);
      ++start_[of[i] + 1];
    }
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    entries_.resize(plants.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < plants.size(); ++i)
      entries_[fill[of[i]]++] = {plants[i].position.x, plants[i].position.y, plants[i].radius, i};
  }
  template <class F>
  void near(glm::dvec2 p, F f) const {
    const auto cx = static_cast<std::int64_t>(std::floor((p.x - x0_) / cell_));
    const auto cy = static_cast<std::int64_t>(std::floor((p.y - y0_) / cell_));
    for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, ny_ - 1); ++y)
      for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0); x <= std::min(cx + 1, nx_ - 1);
           ++x) {
        const auto c = static_cast<std::size_t>(y * nx_ + x);
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) f(entries_[k]);
      }
  }

 private:
  std::size_t cell_of(glm::dvec2 p) const {
    const std::int64_t x = std::clamp<std::int64_t>(
        static_cast<std::int64_t>(std::floor((p.x - x0_) / cell_)), 0, nx_ - 1);
    const std::int64_t y = std::clamp<std::int64_t>(
        static_cast<std::int64_t>(std::floor((p.y - y0_) / cell_)), 0, ny_ - 1);
    return static_cast<std::size_t>(y * nx_ + x);
  }
  double x0_, y0_, cell_;
  std::int64_t nx_ = 0, ny_ = 0;
  std::vector<std::size_t> start_;  // cell c's entries are [start_[c], start_[c + 1])
  std::vector<Entry> entries_;
};

// Whether plant a dominates plant b: the larger circle, then the older, then the first.
bool dominates(const Plant& a, const Plant& b) {
  if (a.radius != b.radius) return a.radius > b.radius;
  if (a.age != b.age) return a.age > b.age;
  return a.id < b.id;
}

// InputError at a species whose habitat is nowhere in the area: it could never establish. The
// habitat is looked at on a 257 × 257 grid over the area (on a terrain, finer than its cells
// where the area is under 257 cells across).
void check_habitats(const spec::CommunityDesc& d, const Terrain& terrain,
                    const std::vector<float>& moisture) {
  constexpr int kSteps = 256;
  const double w = d.area[2] - d.area[0], h = d.area[3] - d.area[1];
  for (const spec::CommunitySpecies& s : d.species) {
    double best = 0.0, lo = 1e300, hi = -1e300, steepest = 0.0;
    for (int j = 0; j <= kSteps && best == 0.0; ++j)
      for (int i = 0; i <= kSteps; ++i) {
        const double x = d.area[0] + w * i / kSteps, y = d.area[1] + h * j / kSteps;
        best = std::max(best, habitat(s, terrain, moisture, x, y));
        const double z = terrain.empty() ? 0.0 : terrain.height(x, y);
        lo = std::min(lo, z);
        hi = std::max(hi, z);
        steepest = std::max(steepest, terrain.empty() ? 0.0 : terrain.slope(x, y));
      }
    if (best > 0.0) continue;
    throw InputError(s.where,
                     "[[community.species]] " + s.species +
                         ": no place in the community's area suits its habitat "
                         "(altitude [" +
                         short_number(s.altitude_min) + ", " + short_number(s.altitude_max) +
                         "] m, slopes to " + short_number(s.slope_max) + "°, moisture [" +
                         short_number(s.moisture_min) + ", " + short_number(s.moisture_max) +
                         "]); the area's ground lies at [" + short_number(std::round(lo)) + ", " +
                         short_number(std::round(hi)) + "] m with slopes to " +
                         short_number(std::round(steepest)) + "°");
  }
}

}  // namespace

double circle_radius(const spec::CommunitySpecies& s, double growth) {
  return s.radius * std::max(0.05, 1.0 - std::exp(-3.0 * growth / s.maturity));
}

std::vector<float> flow_moisture(const Terrain& terrain) {
  const int nx = terrain.columns(), ny = terrain.rows();
  const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto z = [&](std::size_t k) {
    return terrain.at(static_cast<int>(k % nx), static_cast<int>(k / nx));
  };
  // Highest first, ties by index: each vertex has passed on its area before its receiver does.
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return z(a) != z(b) ? z(a) > z(b) : a < b; });
  std::vector<double> area(n, 1.0);
  for (const std::size_t k : order) {
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    std::size_t low = k;
    double drop = 0.0;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int a = i + di, b = j + dj;
        if ((di == 0 && dj == 0) || a < 0 || b < 0 || a >= nx || b >= ny) continue;
        const double d = (z(k) - terrain.at(a, b)) / std::hypot(di, dj);
        if (d > drop) {
          drop = d;
          low = static_cast<std::size_t>(b) * nx + a;
        }
      }
    if (low != k) area[low] += area[k];
  }
  const double top = std::log(*std::max_element(area.begin(), area.end()));
  std::vector<float> m(n);
  for (std::size_t k = 0; k < n; ++k)
    m[k] = top > 0.0 ? static_cast<float>(std::log(area[k]) / top) : 0.5f;
  return m;
}

double habitat(const spec::CommunitySpecies& s, const Terrain& terrain,
               const std::vector<float>& moisture, double x, double y) {
  double altitude = 0.0, slope = 0.0, wet = 0.5, facing = 1.0;
  const glm::dvec2 o = terrain.origin(), e = terrain.extent();
  if (!terrain.empty() && x >= o.x && y >= o.y && x <= o.x + e.x && y <= o.y + e.y) {
    altitude = terrain.height(x, y);
    slope = terrain.slope(x, y);
    const int i = static_cast<int>(std::lround((x - o.x) / terrain.spacing()));
    const int j = static_cast<int>(std::lround((y - o.y) / terrain.spacing()));
    wet = moisture[static_cast<std::size_t>(j) * terrain.columns() + i];
    const glm::vec3 n = terrain.normal(x, y);
    if (std::hypot(n.x, n.y) > 1e-6) {
      // The way the slope faces, clockwise from north (+y).
      const double aspect = std::atan2(n.x, n.y) * 180.0 / kPi;
      facing = 0.5 * (1.0 + std::cos((aspect - s.aspect) * kPi / 180.0));
    }
  }
  const double width = s.altitude_max - s.altitude_min;
  return band(altitude, s.altitude_min, s.altitude_max, 0.05 * width) *
         band(slope, -5.0, s.slope_max, 5.0) * band(wet, s.moisture_min, s.moisture_max, 0.05) *
         (1.0 - s.aspect_preference + s.aspect_preference * facing);
}

namespace {

// One year's establishment: seedlings anywhere, seeds near their parents; each takes by its
// habitat. The newly born, their ids not yet given.
std::vector<Plant> establish(const spec::CommunityDesc& d, const Terrain& terrain,
                             const std::vector<float>& moisture, const std::vector<Plant>& plants,
                             int year) {
  const double w = d.area[2] - d.area[0], h = d.area[3] - d.area[1];
  std::vector<Plant> born;
  auto try_at = [&](int species, glm::dvec2 p, Rng& rng) {
    if (p.x < d.area[0] || p.y < d.area[1] || p.x >= d.area[2] || p.y >= d.area[3]) return;
    const spec::CommunitySpecies& s = d.species[static_cast<std::size_t>(species)];
    if (rng.uniform() >= habitat(s, terrain, moisture, p.x, p.y)) return;
    Plant plant;
    plant.species = species;
    plant.position = p;
    plant.radius = circle_radius(s, 0.0);
    born.push_back(plant);
  };
  // A whole number of draws with the fraction's chance of one more.
  auto draws = [](double expected, Rng& rng) {
    auto count = static_cast<std::uint64_t>(expected);
    if (rng.uniform() < expected - static_cast<double>(count)) ++count;
    return count;
  };
  for (std::size_t k = 0; k < d.species.size(); ++k) {
    Rng rng(derive_key(derive_key(d.seed ^ 0xc0aa17u, static_cast<std::uint64_t>(year)), k));
    const double expected =
        (d.species[k].seedlings + (year == 0 ? d.species[k].sown : 0.0)) * w * h;
    for (std::uint64_t i = draws(expected, rng); i > 0; --i)
      try_at(static_cast<int>(k), {d.area[0] + w * rng.uniform(), d.area[1] + h * rng.uniform()},
             rng);
  }
  for (const Plant& parent : plants) {
    const spec::CommunitySpecies& s = d.species[static_cast<std::size_t>(parent.species)];
    if (parent.age < 0.5 * s.maturity || parent.dominated) continue;
    Rng rng(derive_key(derive_key(d.seed ^ 0x5eed5u, parent.id), static_cast<std::uint64_t>(year)));
    for (std::uint64_t i = draws(s.seeds, rng); i > 0; --i) {
      const double r = -s.dispersal * std::log(std::max(rng.uniform(), 1e-300));
      const double phi = 2.0 * kPi * rng.uniform();
      try_at(parent.species, parent.position + r * glm::dvec2(std::cos(phi), std::sin(phi)), rng);
    }
  }
  return born;
}

// Competition: where two circles overlap the smaller plant is dominated (Plant::dominated set).
// A plant dominated by one of a species no taller than its own (its peers: its kind, or the
// understory under which it is itself understory) has lost its light: true in the result. One
// dominated only by taller species lives on in the shade if it tolerates it.
std::vector<char> compete(const spec::CommunityDesc& d, std::vector<Plant>& plants,
                          double largest) {
  std::vector<char> by_peer(plants.size(), 0);
  // Cells of the largest circle's diameter, or larger on a vast area (at most 2²⁴ of them).
  const double cell = std::max(
      2.0 * largest, std::sqrt((d.area[2] - d.area[0]) * (d.area[3] - d.area[1]) / 0x1p24));
  const Grid grid(plants, d.area, cell);
  for (std::size_t i = 0; i < plants.size(); ++i) {
    Plant& p = plants[i];
    const double layer = d.species[static_cast<std::size_t>(p.species)].radius;
    grid.near(p.position, [&](const Grid::Entry& e) {
      if (e.index == i || by_peer[i]) return;
      const double reach = p.radius + e.radius;
      const double dx = p.position.x - e.x, dy = p.position.y - e.y;
      if (dx * dx + dy * dy >= reach * reach) return;
      const Plant& q = plants[e.index];
      if (!dominates(q, p)) return;
      p.dominated = true;
      by_peer[i] = d.species[static_cast<std::size_t>(q.species)].radius <= layer;
    });
  }
  return by_peer;
}

// Death: the dominated by peers, the dominated that do not tolerate the shade, and the old.
std::vector<Plant> survivors(const spec::CommunityDesc& d, const std::vector<Plant>& plants,
                             const std::vector<char>& by_peer, int year) {
  std::vector<Plant> kept;
  kept.reserve(plants.size());
  for (std::size_t i = 0; i < plants.size(); ++i) {
    const Plant& p = plants[i];
    const spec::CommunitySpecies& s = d.species[static_cast<std::size_t>(p.species)];
    Rng rng(derive_key(derive_key(d.seed ^ 0xdea7u, p.id), static_cast<std::uint64_t>(year)));
    const double u = rng.uniform();
    if (by_peer[i] || (p.dominated && u >= s.shade_tolerance)) continue;
    if (p.age > s.lifespan && rng.uniform() < 0.1) continue;
    kept.push_back(p);
  }
  return kept;
}

CommunityYear census_of(const std::vector<Plant>& plants) {
  CommunityYear census;
  census.alive = plants.size();
  for (const Plant& p : plants) {
    census.mean_radius += p.radius;
    census.mean_biomass += p.radius * p.radius * p.radius;
  }
  if (!plants.empty()) {
    census.mean_radius /= static_cast<double>(plants.size());
    census.mean_biomass /= static_cast<double>(plants.size());
  }
  return census;
}

}  // namespace

Community simulate_community(const spec::CommunityDesc& d, const Terrain& terrain) {
  Community c;
  const std::vector<float> moisture =
      terrain.empty() ? std::vector<float>{} : flow_moisture(terrain);
  check_habitats(d, terrain, moisture);
  double largest = 0.0;
  for (const spec::CommunitySpecies& s : d.species) largest = std::max(largest, s.radius);
  std::uint64_t next_id = 0;
  std::vector<Plant>& plants = c.plants;
  const auto years = static_cast<int>(std::lround(d.years));
  for (int year = 0; year < years; ++year) {
    for (Plant& p : establish(d, terrain, moisture, plants, year)) {
      p.id = next_id++;
      plants.push_back(p);
    }
    if (plants.size() > kMostAlive) {
      throw InputError(d.where,
                       "[community] would have more than 4·10⁶ plants alive at once "
                       "(year " +
                           std::to_string(year + 1) +
                           "); lower its species' seedlings or seeds, or its area");
    }
    for (Plant& p : plants) {
      const spec::CommunitySpecies& s = d.species[static_cast<std::size_t>(p.species)];
      p.age += 1.0;
      p.growth += p.dominated ? 0.25 : 1.0;
      p.radius = circle_radius(s, p.growth);
      p.dominated = false;
    }
    const std::vector<char> by_peer = compete(d, plants, largest);
    plants = survivors(d, plants, by_peer, year);
    c.years.push_back(census_of(plants));
  }
  return c;
}

}  // namespace arbor::scene
