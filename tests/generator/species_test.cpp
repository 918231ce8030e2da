// Tests of a species as the generator grows it: every shipped species grows a valid skeleton.
// Its readers are tested in tests/formats/ (species_toml_test, arbaro_xml_test, ...).
#include "generator/species.h"

#include <filesystem>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "formats/species_file.h"
#include "generator/grow.h"

namespace arbor::generator {

// Every shipped species, whatever its model, grows a skeleton that satisfies the invariants the
// geometry relies on (one root, parents before children, finite points, children no thicker
// than their parents where they start, leaves on stems) and has a sane scale.
TEST(Species, EveryShippedSpeciesGrowsAValidSkeleton) {
  const std::string folder = std::string(ARBOR_SOURCE_DIR) + "/species";
  int grown = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const Species species = formats::load_species(entry.path().string());
    for (std::uint64_t seed : {1u, 8u}) {
      GrowOptions options;
      options.seed = seed;
      options.quality = 0.5;  // half the leaves: the invariants do not depend on their number
      const Skeleton sk = grow_tree(species, options);
      const std::string name = entry.path().filename().string() + " seed " + std::to_string(seed);
      EXPECT_EQ(validate(sk), "") << name;
      EXPECT_EQ(scale_problem(sk), "") << name;
      EXPECT_GE(sk.stems.size(), 1u) << name;
    }
    ++grown;
  }
  EXPECT_GE(grown, 20);  // the shipped species of every model
}

}  // namespace arbor::generator
