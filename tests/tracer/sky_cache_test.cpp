// The sky map cache (tracer/lights/sky_cache.h): a cached map is the computed one bit for bit,
// every input the map depends on changes the key, damaged files are recomputed, "off" is off, and
// the folder keeps at most kMaxSkyCacheFiles maps.
#include "tracer/lights/sky_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "formats/scene_file.h"
#include "formats/scene_keys.h"
#include "temp_files.h"

namespace arbor::tracer {
namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

struct Fixture {
  spec::SkyDesc sky;
  spec::SunDesc sun;
  SkyContext context() const {
    return SkyContext{sky, sun, glm::dvec3(0.3, 0.4, 0.866), kIdentity, 32, 0.25f};
  }
};

// A map made from its context alone, counting how often it was made.
int computed = 0;
SkyMap fake_sky(const SkyContext& c) {
  ++computed;
  SkyMap m;
  m.width = c.width;
  m.height = c.width / 2;
  for (int k = 0; k < m.width * m.height; ++k) {
    m.texels.emplace_back(0.1f * k + static_cast<float>(c.sky.dust_density), 1.0f / (k + 1), 0.5f);
  }
  m.sun_irradiance = glm::vec3(1.5f, 2.5f, 3.5f);
  return m;
}

bool same(const SkyMap& a, const SkyMap& b) {
  return a.width == b.width && a.height == b.height && a.texels.size() == b.texels.size() &&
         std::memcmp(a.texels.data(), b.texels.data(), a.texels.size() * sizeof(glm::vec3)) == 0 &&
         a.sun_irradiance.has_value() == b.sun_irradiance.has_value() &&
         (!a.sun_irradiance || *a.sun_irradiance == *b.sun_irradiance);
}

std::string use_cache(const std::string& name) {
  const std::string dir = testing::fresh_folder(name);
  setenv("ARBOR_CACHE_DIR", dir.c_str(), 1);
  return dir;
}

TEST(SkyCache, ACachedMapIsTheComputedMapBitForBit) {
  const std::string dir = use_cache("sky_cache_same");
  Fixture f;
  f.sky.model = spec::SkyModel::Nishita;
  f.sky.dust_density = 3.0;
  f.sun.irradiance = 2.0;
  setenv("ARBOR_CACHE_DIR", "off", 1);
  const SkyMap fresh = make_sky_map(f.context());  // the real Nishita sky, computed
  EXPECT_TRUE(testing::files_in(dir).empty());
  setenv("ARBOR_CACHE_DIR", dir.c_str(), 1);
  const SkyMap stored = make_sky_map(f.context());  // computed and stored
  ASSERT_EQ(testing::files_in(dir).size(), 1u);
  const SkyMap read = make_sky_map(f.context());  // read back
  EXPECT_TRUE(same(fresh, stored));
  EXPECT_TRUE(same(fresh, read));
  computed = 0;
  cached_sky_map(f.context(), "fake", fake_sky);
  cached_sky_map(f.context(), "fake", fake_sky);
  EXPECT_EQ(computed, 1);  // the second came from the cache
}

// Every [sky] key of the models whose maps are cached (the key table, formats/scene_keys.h: a key
// added there and forgotten in sky_cache_key fails here), each set by a scene file to a value in
// its range other than its default, changes the key; so do the sun's irradiance and direction
// (the context's, from its elevation and azimuth), the map's size and rotation, and the colour
// transform.
TEST(SkyCache, EveryInputOfTheMapChangesTheKey) {
  const auto key_of = [](const std::string& sky_table, const char* model) {
    const spec::SceneDesc d = formats::parse_scene("[sky]\n" + sky_table, "s.toml");
    const SkyContext c{d.sky, d.sun, glm::dvec3(0.3, 0.4, 0.866), kIdentity, 32, 0.25f};
    return sky_cache_key(c, model);
  };
  int keys = 0;
  for (const char* model : {"nishita", "atmosphere"}) {
    const std::string chosen = std::string("model = \"") + model + "\"\n";
    const std::uint64_t base = key_of(chosen, model);
    EXPECT_EQ(key_of(chosen, model), base);
    EXPECT_NE(key_of(chosen, "preetham"), base);
    for (const formats::Key<spec::SkyDesc>& k : formats::sky_keys()) {
      if (k.name == "model" || !formats::belongs_to(k.belongs, model)) continue;
      ASSERT_EQ(k.kind, formats::KeyKind::Number) << k.name << ": give it a value below";
      // A value a user might give, inside the range and off every default.
      const double lo = k.range.lo, hi = std::min(k.range.hi, lo + 100.0);
      const std::string value = formats::exact_number(lo + 0.37 * (hi - lo));
      EXPECT_NE(key_of(chosen + std::string(k.name) + " = " + value + "\n", model), base)
          << model << ": sky." << k.name << " = " << value;
      ++keys;
    }
  }
  EXPECT_GE(keys, 9);  // nishita's 4, the atmosphere's 7 (the table is read, not skipped)
  Fixture f;
  f.sky.model = spec::SkyModel::Nishita;
  const std::uint64_t base = sky_cache_key(f.context(), "nishita");
  const auto changed = [&](auto&& change) {
    Fixture g = f;
    change(g);
    return sky_cache_key(g.context(), "nishita") != base;
  };
  EXPECT_TRUE(changed([](Fixture& g) { g.sky.dust_density = std::nextafter(1.0, 2.0); }));
  EXPECT_TRUE(changed([](Fixture& g) { g.sun.irradiance = 2.9; }));
  const auto context_changed = [&](auto&& change) {
    SkyContext c = f.context();
    change(c);
    return sky_cache_key(c, "nishita") != base;
  };
  EXPECT_TRUE(context_changed(
      [](SkyContext& c) { c.sun_direction.z = std::nextafter(c.sun_direction.z, 1.0); }));
  EXPECT_TRUE(context_changed([](SkyContext& c) { c.width = 64; }));
  EXPECT_TRUE(context_changed([](SkyContext& c) { c.rotation = 0.5f; }));
  const imaging::ColorTransform doubled = [](float* rgb) { rgb[0] *= 2.0f; };
  const SkyContext other{f.sky, f.sun, f.context().sun_direction, doubled, 32, 0.25f};
  EXPECT_NE(sky_cache_key(other, "nishita"), base);
  // Which key gave the atmosphere's aerosols (the same dust by turbidity or by dust_density).
  Fixture a = f;
  a.sky.model = spec::SkyModel::Atmosphere;
  const std::uint64_t atmosphere = sky_cache_key(a.context(), "atmosphere");
  a.sky.dust_given = true;
  EXPECT_NE(sky_cache_key(a.context(), "atmosphere"), atmosphere);
}

TEST(SkyCache, DamagedOrTruncatedFilesAreComputedAgain) {
  const std::string dir = use_cache("sky_cache_damaged");
  Fixture f;
  computed = 0;
  const SkyMap first = cached_sky_map(f.context(), "fake", fake_sky);
  const std::string file = dir + "/" + testing::files_in(dir).at(0);
  {  // one flipped bit in the texels
    std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
    io.seekg(100);
    char byte = 0;
    io.read(&byte, 1);
    byte = static_cast<char>(byte ^ 1);
    io.seekp(100);
    io.write(&byte, 1);
  }
  EXPECT_TRUE(same(cached_sky_map(f.context(), "fake", fake_sky), first));
  EXPECT_EQ(computed, 2);
  std::filesystem::resize_file(file, 200);  // truncated
  EXPECT_TRUE(same(cached_sky_map(f.context(), "fake", fake_sky), first));
  EXPECT_EQ(computed, 3);
  EXPECT_TRUE(same(cached_sky_map(f.context(), "fake", fake_sky), first));
  EXPECT_EQ(computed, 3);  // rewritten whole
}

TEST(SkyCache, OffMeansNoFilesAndTheFolderKeepsTheNewestMaps) {
  const std::string dir = use_cache("sky_cache_bounded");
  Fixture f;
  for (int i = 0; i < kMaxSkyCacheFiles + 6; ++i) {
    f.sky.dust_density = 1.0 + i;
    cached_sky_map(f.context(), "fake", fake_sky);
  }
  EXPECT_EQ(testing::files_in(dir).size(), static_cast<std::size_t>(kMaxSkyCacheFiles));
  const std::string off = use_cache("sky_cache_off");
  setenv("ARBOR_CACHE_DIR", "off", 1);
  computed = 0;
  cached_sky_map(f.context(), "fake", fake_sky);
  cached_sky_map(f.context(), "fake", fake_sky);
  EXPECT_EQ(computed, 2);
  EXPECT_TRUE(testing::files_in(off).empty());
  unsetenv("ARBOR_CACHE_DIR");
}

}  // namespace
}  // namespace arbor::tracer
