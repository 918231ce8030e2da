// A disk cache of computed sky maps (the Nishita sky takes about 1 CPU-s to compute, the
// atmosphere's about 3 — bench/sky_bench map — and each is the same for every render, farm unit
// and frame with the same sky and sun). A map is stored under a
// key over everything it depends on — the model's parameters, the sun, the map's width and
// rotation, the colour transform's values, and the executable itself (its size, time and inode,
// so a rebuilt arbor never reads an older build's maps) — and read back bit for bit, so a cached
// sky renders the identical image. A damaged, foreign or truncated file is ignored and replaced.
//
// Where: $ARBOR_CACHE_DIR, else $XDG_CACHE_HOME/arbor, else $HOME/.cache/arbor; ARBOR_CACHE_DIR
// set to "off" (or an empty value) turns the cache off. At most kMaxSkyCacheFiles maps are kept
// (the oldest removed first). Failing to read or write the cache never fails a render.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "tracer/lights/sky_model.h"

namespace arbor::tracer {

inline constexpr int kMaxSkyCacheFiles = 64;

// The folder of the cache, or "" when it is off.
std::string sky_cache_dir();

// The key of the map `context` asks of `model` (a name for the file and the hash).
std::uint64_t sky_cache_key(const SkyContext& context, const char* model);

// The map of `context` from the cache, or computed by `compute` and stored.
SkyMap cached_sky_map(const SkyContext& context, const char* model,
                      const std::function<SkyMap(const SkyContext&)>& compute);

}  // namespace arbor::tracer
