// The sky map cache (tracer/lights/sky_cache.h): a cached map is the computed one bit for bit,
// every input the map depends on changes the key, damaged files are recomputed, "off" is off, and
// the folder keeps at most kMaxSkyCacheFiles maps.
#include "tracer/lights/sky_cache.h"

#include <cstdlib>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "temp_files.h"

namespace arbor::tracer {
namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

struct Fixture {
  scene::SkySpec sky;
  scene::SunSpec sun;
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
  f.sky.model = formats::SkyModel::Nishita;
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

TEST(SkyCache, EveryInputOfTheMapChangesTheKey) {
  Fixture f;
  const std::uint64_t base = sky_cache_key(f.context(), "nishita");
  EXPECT_EQ(sky_cache_key(f.context(), "nishita"), base);
  EXPECT_NE(sky_cache_key(f.context(), "preetham"), base);
  const auto changed = [&](auto&& change) {
    Fixture g = f;
    change(g);
    return sky_cache_key(g.context(), "nishita") != base;
  };
  EXPECT_TRUE(changed([](Fixture& g) { g.sky.dust_density = std::nextafter(1.0, 2.0); }));
  EXPECT_TRUE(changed([](Fixture& g) { g.sky.air_density = 1.01; }));
  EXPECT_TRUE(changed([](Fixture& g) { g.sky.ozone_density = 0.99; }));
  EXPECT_TRUE(changed([](Fixture& g) { g.sky.altitude = 10.0; }));
  EXPECT_TRUE(changed([](Fixture& g) { g.sky.turbidity = 3.0; }));
  EXPECT_TRUE(changed([](Fixture& g) { g.sun.irradiance = 1.0; }));
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
  // The atmosphere's own inputs: its ground and which key gave the aerosols.
  Fixture a = f;
  a.sky.model = formats::SkyModel::Atmosphere;
  const std::uint64_t atmosphere = sky_cache_key(a.context(), "atmosphere");
  const auto atmosphere_changed = [&](auto&& change) {
    Fixture g = a;
    change(g);
    return sky_cache_key(g.context(), "atmosphere") != atmosphere;
  };
  EXPECT_TRUE(atmosphere_changed([](Fixture& g) { g.sky.ground_albedo = 0.3; }));
  EXPECT_TRUE(atmosphere_changed([](Fixture& g) { g.sky.visibility = 40.0; }));
  EXPECT_TRUE(atmosphere_changed([](Fixture& g) { g.sky.dust_given = true; }));
  EXPECT_TRUE(atmosphere_changed([](Fixture& g) { g.sky.turbidity_given = true; }));
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
