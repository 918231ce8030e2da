// A plant community (docs/landscape.md, "Plant communities"): its species grown together over
// years as Lane & Prusinkiewicz's circles of influence (2002, §3): seedlings established where the
// habitat allows and seeds dispersed near their parents, each plant's circle growing with age,
// and where two circles overlap the smaller plant dominated. Dominated by its own kind (or by a
// species no taller) it dies; overtopped by a taller species it dies unless shade tolerant, and a
// tolerant one lives on under the canopy, growing at a quarter of the rate and bearing no seed.
// What is left after the years is the community: every plant with its species, age and size.
// Deterministic: a function of the [community] table and the terrain, on one thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "spec/scene_desc.h"
#include "scene/terrain.h"

namespace arbor::scene {

struct Plant {
  int species = 0;         // index into CommunityDesc::species
  glm::dvec2 position{0};  // world x, y
  double age = 0.0;        // years
  double growth = 0.0;     // years of full growth (a dominated plant grows at a quarter)
  double radius = 0.0;     // metres: its circle of influence
  bool dominated = false;  // under a larger plant's circle this year
  std::uint64_t id = 0;    // its number in the order of establishment
};

// One year's census: what lived at its end.
struct CommunityYear {
  std::size_t alive = 0;
  double mean_radius = 0.0;   // metres
  double mean_biomass = 0.0;  // radius³, m³ (the self-thinning law's mass)
};

struct Community {
  std::vector<Plant> plants;         // alive after the last year
  std::vector<CommunityYear> years;  // one per year
};

// The habitat's suitability of (x, y) for species `s`, in [0, 1]: altitude band, slope, aspect
// and moisture, each 0 outside its band and rising to 1 over its edges inside it (altitude 5 % of
// the band, slope 5°, moisture 0.05). On no terrain the ground is flat, at altitude 0 and
// moisture 0.5.
double habitat(const spec::CommunitySpecies& s, const Terrain& terrain,
               const std::vector<float>& moisture, double x, double y);

// The terrain's flow moisture per vertex, in [0, 1]: the log of the area draining through it
// (D8, each vertex passing its area to its lowest neighbour) over the log of the largest.
std::vector<float> flow_moisture(const Terrain& terrain);

// A circle of influence's radius after `growth` years: radius (1 − e^(−3 growth / maturity)), at
// least 5 % of radius (a seedling's).
double circle_radius(const spec::CommunitySpecies& s, double growth);

// The community of `d` on `terrain` (empty: the plane). InputError at the table when more than
// 4·10⁶ plants would be alive at once.
Community simulate_community(const spec::CommunityDesc& d, const Terrain& terrain);

}  // namespace arbor::scene
