// Up-front memory estimate of a render.
#include "scene/render_budget.h"

#include "scene/terrain.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "common/error.h"
#include "scene/terrain.h"

namespace arbor::scene {

namespace {

// Outside the film (which states its own, FilmCosts): calibrated, see render_budget.h.
constexpr std::uint64_t kBytesPerPixel = 72;   // image and beauty, PNG included
constexpr std::uint64_t kBytesPerChannel = 8;  // each EXR channel: its pixels and encoding
// A distinct grass blade: its arrays (136 bytes), Embree's copy of its normals and its BVH
// (bench/meadow.sh measures the whole).
constexpr std::uint64_t kBytesPerBlade = 400;
// A terrain's vertex: 12 bytes of its own and 12 of Embree's compact grid BVH (a 4001 × 4001
// terrain peaked 378 MB over an empty scene: 23.6 bytes a vertex), rounded up.
constexpr std::uint64_t kBytesPerTerrainVertex = 26;
constexpr std::uint64_t kBaseline = 256ull << 20;  // libraries, OCIO, Embree's device

double gigabytes(std::uint64_t bytes) { return static_cast<double>(bytes) / double(1ull << 30); }

}  // namespace

MemoryEstimate estimate_render_memory(const spec::SceneDesc& s, const FilmCosts& film,
                                      std::uint64_t record_passes) {
  MemoryEstimate e;
  std::uint64_t channels = 4, extras = 0;
  for (std::size_t i = 0; i < imaging::kAovCount; ++i) {
    const imaging::Aov a = static_cast<imaging::Aov>(i);
    if (!s.output.aovs.has(a)) continue;
    channels += a == imaging::Aov::Depth || a == imaging::Aov::Samples ||
                        a == imaging::Aov::ObjectId || a == imaging::Aov::MaterialId
                    ? 1
                : a == imaging::Aov::Treemaker ? film.treemaker_extras
                : a == imaging::Aov::CryptoObject || a == imaging::Aov::CryptoMaterial ? 12
                                                                                       : 3;
    if (a == imaging::Aov::Treemaker) extras = film.treemaker_extras;
  }
  // The id slots count like extras: in the film's sums and in every pass record.
  if (s.output.wants_ids()) extras += film.id_sums;
  const std::uint64_t pixels =
      static_cast<std::uint64_t>(s.render.width) * static_cast<std::uint64_t>(s.render.height);
  const std::uint64_t sums = film.sums + extras;
  const std::uint64_t kept =
      film.state + film.sum * sums + record_passes * film.sum * (sums + film.record_extra);
  e.image_bytes = pixels * (kBytesPerPixel + kept + kBytesPerChannel * channels);
  e.instances = s.trees.size();
  for (const spec::ForestDesc& f : s.forests) e.instances += static_cast<std::uint64_t>(f.count);
  e.instance_bytes = e.instances * kBytesPerInstance;
  const spec::MeadowDesc& m = s.meadow;
  if (m.density > 0.0) {
    // On a terrain each cell holds two halves, and each tile is kept at four densities.
    const double halves = s.terrain.enabled ? 2.0 : 1.0, levels = s.terrain.enabled ? 1.875 : 1.0;
    const double cells = spec::meadow_cells(m) * halves;
    const double blades = m.density * m.tile * m.tile * m.tiles * levels;
    e.meadow_bytes = static_cast<std::uint64_t>(cells) * kBytesPerInstance +
                     static_cast<std::uint64_t>(blades) * kBytesPerBlade;
  }
  e.terrain_bytes = terrain_vertices(s.terrain) * kBytesPerTerrainVertex;
  return e;
}

std::uint64_t usable_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  std::uint64_t usable = pages > 0 && page > 0
                             ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page)
                             : ~0ull;
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
      usable = std::min<std::uint64_t>(usable, limit.rlim_cur);
    }
  }
  return usable;
}

std::uint64_t geometry_budget(const spec::SceneDesc& s, const FilmCosts& film, bool force,
                              std::uint64_t usable, std::uint64_t record_passes) {
  if (force) return 0;
  const std::uint64_t used = estimate_render_memory(s, film, record_passes).total() + kBaseline;
  return usable > used ? usable - used : 1;
}

void check_render_memory(const spec::SceneDesc& s, const FilmCosts& film, bool force,
                         std::uint64_t usable, std::uint64_t record_passes) {
  const MemoryEstimate e = estimate_render_memory(s, film, record_passes);
  if (force || e.total() + kBaseline <= usable) return;
  SourceLocation where{s.path, 0, 0};
  int largest = 0;
  for (const spec::ForestDesc& f : s.forests) {
    if (f.count > largest && e.instance_bytes > e.image_bytes &&
        e.instance_bytes > e.meadow_bytes) {
      largest = f.count;
      where = f.where;
    }
  }
  if (e.meadow_bytes > e.image_bytes && e.meadow_bytes > e.instance_bytes) where = s.meadow.where;
  if (e.terrain_bytes > std::max({e.image_bytes, e.instance_bytes, e.meadow_bytes}))
    where = s.terrain.where;
  char buf[560];
  std::snprintf(
      buf, sizeof buf,
      "the render would need about %.1f GB (a %dx%d image with its outputs: %.1f GB; %llu "
      "trees: %.1f GB; the meadow: %.1f GB; the terrain: %.1f GB), more than the %.1f GB this "
      "process may use; lower the size, the count or the terrain's resolution, or use --force to "
      "render it anyway",
      gigabytes(e.total() + kBaseline), s.render.width, s.render.height, gigabytes(e.image_bytes),
      static_cast<unsigned long long>(e.instances), gigabytes(e.instance_bytes),
      gigabytes(e.meadow_bytes), gigabytes(e.terrain_bytes), gigabytes(usable));
  throw InputError(where, buf);
}

void check_forest_budget(const spec::ForestDesc& f, std::size_t before, std::size_t after,
                         std::uint64_t budget) {
  if (budget == 0) return;
  const double each = 2.0 * static_cast<double>(after - before);
  const double projected = 2.0 * static_cast<double>(before) + each * f.variants;
  if (projected <= static_cast<double>(budget)) return;
  char buf[400];
  std::snprintf(
      buf, sizeof buf,
      "the forest's %d variants would need about %.1f GB of geometry (%.0f MB each, with "
      "Embree's structures), more than the %.1f GB left for trees; lower variants, or use "
      "--force to render it anyway",
      f.variants, projected / double(1ull << 30), each / double(1ull << 20),
      static_cast<double>(budget) / double(1ull << 30));
  throw InputError(f.where, buf);
}

}  // namespace arbor::scene
