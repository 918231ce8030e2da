// Tests of the plant community's simulation (scene/community.h), by the statistics ecologists
// read a stand by: canopy trees inhibit each other (few pairs closer than a crown's radius, and
// Clark & Evans's 1954 ratio of the mean nearest-neighbour distance to a random pattern's above
// 1.1), the shade-tolerant understory clusters around its parents (the ratio below 1), the
// stand thins itself as its trees grow (Yoda's law: mean mass ∝ density^(−3/2)), no plant stands
// outside its habitat, and the community is a function of its table.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/math.h"
#include "scene/community.h"

namespace arbor::scene {
namespace {

spec::CommunitySpecies canopy() {
  spec::CommunitySpecies s;
  s.species = "canopy";
  s.radius = 4.0;
  s.maturity = 40.0;
  s.seedlings = 5e-3;
  s.seeds = 2.0;
  s.dispersal = 10.0;
  return s;
}

spec::CommunitySpecies understory() {
  spec::CommunitySpecies s;
  s.species = "understory";
  s.radius = 1.0;
  s.maturity = 15.0;
  s.seedlings = 2e-4;
  s.seeds = 0.5;
  s.dispersal = 2.0;
  s.shade_tolerance = 0.9;
  return s;
}

spec::CommunityDesc community(std::vector<spec::CommunitySpecies> species, double side,
                              double years) {
  spec::CommunityDesc d;
  d.enabled = true;
  d.area = {-0.5 * side, -0.5 * side, 0.5 * side, 0.5 * side};
  d.years = years;
  d.species = std::move(species);
  return d;
}

// The points of `plants` for which `keep` holds.
template <class F>
std::vector<glm::dvec2> points(const std::vector<Plant>& plants, F keep) {
  std::vector<glm::dvec2> p;
  for (const Plant& plant : plants)
    if (keep(plant)) p.push_back(plant.position);
  return p;
}

// Clark & Evans's R (1954) of the points in a square of side `side` centred on the origin: the
// mean distance to the nearest neighbour over 1 / (2 √density), for the points at least `guard`
// from the edge (whose nearest neighbour is not outside the square). 1: random; > 1: regular;
// < 1: clustered.
double clark_evans(const std::vector<glm::dvec2>& p, double side, double guard) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::max(std::abs(p[i].x), std::abs(p[i].y)) > 0.5 * side - guard) continue;
    double nearest = 1e300;
    for (std::size_t j = 0; j < p.size(); ++j)
      if (j != i) nearest = std::min(nearest, glm::length(p[i] - p[j]));
    sum += nearest;
    ++n;
  }
  const double density = static_cast<double>(p.size()) / (side * side);
  return (sum / static_cast<double>(n)) * 2.0 * std::sqrt(density);
}

// The pair-correlation function averaged over distances below r: the pairs found closer than r
// over the pairs a random pattern of the same density has (ρ π r² per point), for points at least
// r from the edge.
double pair_correlation_below(const std::vector<glm::dvec2>& p, double side, double r) {
  std::size_t pairs = 0, n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::max(std::abs(p[i].x), std::abs(p[i].y)) > 0.5 * side - r) continue;
    ++n;
    for (std::size_t j = 0; j < p.size(); ++j) pairs += j != i && glm::length(p[i] - p[j]) < r;
  }
  const double density = static_cast<double>(p.size()) / (side * side);
  return static_cast<double>(pairs) / (static_cast<double>(n) * density * kPi * r * r);
}

// A canopy species over a shade-tolerant understory on 200 × 200 m of flat ground, 150 years.
const Community& mixed_stand() {
  static const Community c =
      simulate_community(community({canopy(), understory()}, 200.0, 150.0), Terrain{});
  return c;
}

TEST(Community, CanopyTreesInhibitEachOther) {
  const Community& c = mixed_stand();
  // The largest size class: canopy trees past three quarters of the full radius.
  const auto big =
      points(c.plants, [](const Plant& p) { return p.species == 0 && p.radius > 3.0; });
  ASSERT_GT(big.size(), 200u);
  double mean_radius = 0.0;
  std::size_t trees = 0;
  for (const Plant& p : c.plants)
    if (p.species == 0) mean_radius += p.radius, ++trees;
  mean_radius /= static_cast<double>(trees);
  // Measured 0 and 1.73 (a random pattern: 1 and 1).
  EXPECT_LT(pair_correlation_below(big, 200.0, mean_radius), 0.5);
  EXPECT_GT(clark_evans(big, 200.0, 10.0), 1.1);
}

TEST(Community, TheUnderstoryClustersAndLivesUnderTheCanopy) {
  const Community& c = mixed_stand();
  const auto under = points(c.plants, [](const Plant& p) { return p.species == 1; });
  ASSERT_GT(under.size(), 300u);
  EXPECT_LT(clark_evans(under, 200.0, 10.0), 1.0);  // measured 0.77
  // Some of it stands under a canopy tree's circle; an intolerant understory none.
  auto shaded = [](const Community& stand) {
    std::size_t n = 0, under_canopy = 0;
    for (const Plant& u : stand.plants) {
      if (u.species != 1) continue;
      ++n;
      for (const Plant& t : stand.plants)
        if (t.species == 0 && t.radius > u.radius &&
            glm::length(t.position - u.position) < t.radius + u.radius) {
          ++under_canopy;
          break;
        }
    }
    return static_cast<double>(under_canopy) / static_cast<double>(n);
  };
  EXPECT_GT(shaded(c), 0.1);
  spec::CommunitySpecies intolerant = understory();
  intolerant.shade_tolerance = 0.0;
  EXPECT_EQ(shaded(simulate_community(community({canopy(), intolerant}, 200.0, 150.0), Terrain{})),
            0.0);
}

// Yoda's law of self-thinning (Yoda et al. 1963): in a crowded even-aged stand the mean mass of a
// plant rises as the density falls, mass ∝ density^(−3/2). Fitted over the years of thinning:
// after half the sown plants have died and before the trees reach 90 % of their full size.
TEST(Community, AnEvenAgedStandThinsItselfByYodasLaw) {
  spec::CommunitySpecies s = canopy();
  s.sown = 0.5;
  s.seedlings = 0.0;
  s.seeds = 0.0;
  const Community c = simulate_community(community({s}, 100.0, 100.0), Terrain{});
  std::vector<double> x, y;
  for (const CommunityYear& year : c.years)
    if (year.alive < c.years.front().alive / 2 && year.mean_radius < 0.9 * s.radius) {
      x.push_back(std::log(static_cast<double>(year.alive)));
      y.push_back(std::log(year.mean_biomass));
    }
  ASSERT_GE(x.size(), 10u);
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) mx += x[k] / n, my += y[k] / n;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
  }
  EXPECT_NEAR(sxy / sxx, -1.5, 0.3);  // measured -1.58
}

// Ridged mountains 200 m across with 120 m of relief, as the habitat's ground.
Terrain mountains() {
  spec::TerrainDesc t;
  t.enabled = true;
  t.kind = spec::TerrainKind::Mountains;
  t.size = 200;
  t.resolution = 2;
  t.relief = 120;
  t.seed = 5;
  return Terrain(t);
}

TEST(Community, NoPlantStandsOutsideItsHabitat) {
  const Terrain terrain = mountains();
  spec::CommunitySpecies s = canopy();
  s.altitude_min = 30.0;
  s.altitude_max = 70.0;
  s.slope_max = 35.0;
  s.radius = 2.0;
  s.seedlings = 2e-2;
  spec::CommunitySpecies wet = understory();
  wet.moisture_min = 0.5;
  wet.seedlings = 2e-2;
  const Community c = simulate_community(community({s, wet}, 190.0, 40.0), terrain);
  const std::vector<float> moisture = flow_moisture(terrain);
  std::size_t trees = 0, shrubs = 0;
  for (const Plant& p : c.plants) {
    const double x = p.position.x, y = p.position.y;
    if (p.species == 0) {
      ++trees;
      EXPECT_GE(terrain.height(x, y), 30.0);
      EXPECT_LE(terrain.height(x, y), 70.0);
      EXPECT_LE(terrain.slope(x, y), 35.0);
    } else {
      ++shrubs;
      EXPECT_GT(habitat(wet, terrain, moisture, x, y), 0.0);
    }
  }
  EXPECT_GT(trees, 30u);  // measured 44
  EXPECT_GT(shrubs, 50u);
  // A band the terrain does not reach is refused, naming the species.
  s.altitude_min = 500.0;
  s.altitude_max = 600.0;
  try {
    simulate_community(community({s}, 190.0, 10.0), terrain);
    ADD_FAILURE() << "a habitat nowhere in the area was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("canopy: no place in the community's area suits"),
              std::string::npos)
        << e.what();
  }
}

TEST(Community, IsAFunctionOfItsTable) {
  const spec::CommunityDesc d = community({canopy(), understory()}, 100.0, 60.0);
  const Community a = simulate_community(d, mountains()), b = simulate_community(d, mountains());
  ASSERT_EQ(a.plants.size(), b.plants.size());
  for (std::size_t i = 0; i < a.plants.size(); ++i) {
    EXPECT_EQ(a.plants[i].position, b.plants[i].position);
    EXPECT_EQ(a.plants[i].radius, b.plants[i].radius);
    EXPECT_EQ(a.plants[i].id, b.plants[i].id);
  }
  spec::CommunityDesc other = d;
  other.seed = 2;
  EXPECT_NE(simulate_community(other, mountains()).plants.front().position,
            a.plants.front().position);
}

}  // namespace
}  // namespace arbor::scene
