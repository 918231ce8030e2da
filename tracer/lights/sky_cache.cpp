// The sky map cache: a key over a map's inputs, files of raw texels with a checksum.
#include "tracer/lights/sky_cache.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

#include "common/atomic_file.h"
#include "common/input_file.h"

namespace arbor::tracer {

namespace {

constexpr char kMagic[16] = "arbor-sky-map-1";

template <class T>
std::uint64_t mix(std::uint64_t h, const T& value) {
  return fnv1a_bytes(&value, sizeof value, h);
}

// Identifies the running executable's build: a rebuilt or reinstalled arbor has another.
std::uint64_t executable_identity() {
  struct stat st {};
  if (stat("/proc/self/exe", &st) != 0) return 0;
  std::uint64_t h = mix(0xcbf29ce484222325ull, st.st_size);
  h = mix(h, st.st_mtim.tv_sec);
  h = mix(h, st.st_mtim.tv_nsec);
  h = mix(h, st.st_ino);
  return mix(h, st.st_dev);
}

std::string file_for(const std::string& dir, std::uint64_t key) {
  char name[40];
  std::snprintf(name, sizeof name, "sky-%016llx.bin", static_cast<unsigned long long>(key));
  return dir + "/" + name;
}

struct Header {
  char magic[16];
  std::uint64_t key;
  std::int32_t width, height;
  std::int32_t has_sun, pad;
  float sun[3], pad2;
};

std::optional<SkyMap> read_map(const std::string& path, std::uint64_t key, int width) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  Header h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) return std::nullopt;
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.key != key || h.width != width ||
      h.height != width / 2) {
    return std::nullopt;
  }
  SkyMap map;
  map.width = h.width;
  map.height = h.height;
  map.texels.resize(static_cast<std::size_t>(map.width) * map.height);
  const std::size_t bytes = map.texels.size() * sizeof(glm::vec3);
  std::uint64_t sum = 0;
  if (!in.read(reinterpret_cast<char*>(map.texels.data()), static_cast<std::streamsize>(bytes)) ||
      !in.read(reinterpret_cast<char*>(&sum), sizeof sum) || in.peek() != EOF) {
    return std::nullopt;
  }
  if (fnv1a_bytes(map.texels.data(), bytes, fnv1a_bytes(&h, sizeof h)) != sum) return std::nullopt;
  if (h.has_sun) map.sun_irradiance = glm::vec3(h.sun[0], h.sun[1], h.sun[2]);
  return map;
}

void write_map(const std::string& dir, const std::string& path, std::uint64_t key,
               const SkyMap& map) {
  std::filesystem::create_directories(dir);
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.key = key;
  h.width = map.width;
  h.height = map.height;
  h.has_sun = map.sun_irradiance ? 1 : 0;
  if (map.sun_irradiance) {
    h.sun[0] = map.sun_irradiance->x;
    h.sun[1] = map.sun_irradiance->y;
    h.sun[2] = map.sun_irradiance->z;
  }
  const std::size_t bytes = map.texels.size() * sizeof(glm::vec3);
  const std::uint64_t sum = fnv1a_bytes(map.texels.data(), bytes, fnv1a_bytes(&h, sizeof h));
  AtomicFile out(path, true);
  out.write(&h, sizeof h);
  out.write(map.texels.data(), bytes);
  out.write(&sum, sizeof sum);
  out.commit();
  // Keep the newest kMaxSkyCacheFiles maps.
  std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> maps;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.rfind("sky-", 0) == 0 && name.size() > 4 &&
        name.substr(name.size() - 4) == ".bin") {
      maps.emplace_back(e.last_write_time(), e.path());
    }
  }
  if (maps.size() <= static_cast<std::size_t>(kMaxSkyCacheFiles)) return;
  std::sort(maps.begin(), maps.end());
  for (std::size_t i = 0; i + kMaxSkyCacheFiles < maps.size(); ++i) {
    std::error_code ignored;
    std::filesystem::remove(maps[i].second, ignored);
  }
}

}  // namespace

std::string sky_cache_dir() {
  if (const char* d = std::getenv("ARBOR_CACHE_DIR")) {
    const std::string dir(d);
    return dir == "off" ? std::string() : dir;
  }
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/arbor";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/.cache/arbor";
  return {};
}

std::uint64_t sky_cache_key(const SkyContext& c, const char* model) {
  std::uint64_t h = fnv1a_bytes(model, std::strlen(model));
  h = mix(h, executable_identity());
  h = mix(h, c.sky.turbidity);
  h = mix(h, c.sky.air_density);
  h = mix(h, c.sky.dust_density);
  h = mix(h, c.sky.ozone_density);
  h = mix(h, c.sky.altitude);
  if (c.sky.model == spec::SkyModel::Atmosphere) {
    h = mix(h, c.sky.visibility);
    h = mix(h, spec::ground_albedo_under(c.sky));
    h = mix(h, static_cast<double>(c.sky.turbidity_given) + 2.0 * c.sky.dust_given);
  }
  h = mix(h, c.sun.irradiance);
  h = mix(h, c.sun_direction.x);
  h = mix(h, c.sun_direction.y);
  h = mix(h, c.sun_direction.z);
  h = mix(h, c.width);
  h = mix(h, c.rotation);
  // The colour transform by its values: XYZ's basis and a colour through it.
  const float probes[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.31f, 0.52f, 0.17f}};
  for (const auto& p : probes) {
    float rgb[3] = {p[0], p[1], p[2]};
    c.xyz_to_linear(rgb);
    h = fnv1a_bytes(rgb, sizeof rgb, h);
  }
  return h;
}

SkyMap cached_sky_map(const SkyContext& context, const char* model,
                      const std::function<SkyMap(const SkyContext&)>& compute) {
  const std::string dir = sky_cache_dir();
  if (dir.empty()) return compute(context);
  const std::uint64_t key = sky_cache_key(context, model);
  const std::string path = file_for(dir, key);
  try {
    if (std::optional<SkyMap> map = read_map(path, key, context.width)) return std::move(*map);
  } catch (...) {
    // An unreadable cache is no cache.
  }
  SkyMap map = compute(context);
  try {
    write_map(dir, path, key, map);
  } catch (...) {
    // A full disk or a read-only home: the render goes on without the cache.
  }
  return map;
}

}  // namespace arbor::tracer
