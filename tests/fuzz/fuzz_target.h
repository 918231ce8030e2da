// What every fuzz target shares: the bytes as text, the outcomes that are not findings (an
// InputError is bad input refused; a RuntimeFailure is a size limit), and the checks that turn a
// silently wrong result into a crash the fuzzer reports.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/error.h"
#include "generator/grow.h"
#include "generator/skeleton.h"
#include "generator/species.h"
#include "generator/geometry/tree_geometry.h"

namespace arbor::fuzz {

// Aborts (a finding) with a message when `ok` is false.
inline void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz: invariant broken: %s\n", what);
    std::abort();
  }
}

inline bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline bool finite(const glm::vec4& v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }

// A grown or read tree must be valid, and small ones must turn into finite geometry.
inline void check_tree(const generator::Skeleton& sk,
                       const generator::GeometryOptions& options = {}) {
  require(generator::validate(sk).empty(), "the skeleton is valid");
  require(generator::scale_problem(sk).empty(), "the tree is within scale");
  if (sk.points.size() > 3000 || sk.leaves.size() > 20000) return;
  const generator::TreeGeometry g = generator::build_tree_geometry(sk, options);
  for (const glm::vec4& p : g.curves.points) require(finite(p), "curve points are finite");
  for (const glm::vec4& t : g.curves.tangents) require(finite(t), "curve tangents are finite");
  for (const glm::vec3& v : g.grids.vertices) require(finite(v), "grid vertices are finite");
  for (const glm::vec3& n : g.grids.normals) require(finite(n), "grid normals are finite");
  for (const glm::vec3& v : g.leaves.positions) require(finite(v), "leaf vertices are finite");
  for (const glm::vec3& v : g.cards.corners) require(finite(v), "leaf card corners are finite");
}

// Grows a species of any model when it is small (a few thousand stems) and checks the tree.
inline void grow_and_check(const generator::Species& species) {
  generator::GrowOptions o;
  o.max_stems = 2000;
  o.max_leaves = 20000;
  check_tree(generator::grow_tree(species, o), generator::geometry_options_for(species));
}

}  // namespace arbor::fuzz

// Defines the libFuzzer entry point around BODY, which reads `text`.
#define ARBOR_FUZZ_TARGET(BODY)                                                       \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    const std::string text(reinterpret_cast<const char*>(data), size);                \
    try {                                                                             \
      BODY                                                                            \
    } catch (const ::arbor::InputError&) {                                            \
    } catch (const ::arbor::RuntimeFailure&) {                                        \
    }                                                                                 \
    return 0;                                                                         \
  }
