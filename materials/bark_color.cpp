// Bark colour from the bark coordinates (bark_color.h).
#include "materials/bark_color.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/common.hpp>

#include "common/math.h"
#include "common/rng.h"

namespace arbor::materials {

namespace {

float smoothstep(float lo, float hi, float x) {
  const float t = std::clamp((x - lo) / (hi - lo), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// A uniform number in [0, 1) from a key.
float unit(std::uint64_t key) { return static_cast<float>(mix64(key) >> 40) * 0x1.0p-24f; }

}  // namespace

namespace {

// The coverage at (u, v) metres of a grid of cells `cell_u` × `cell_v`, one mark each of half
// extents up to `width` / 2 × `height` / 2 (0.6–1.4× that, by the cell's hash), placed inside its
// cell by the hash.
float cell_mark(double u, double v, double cell_u, double cell_v, std::uint64_t key, float width,
                float height) {
  const double iu = std::floor(u / cell_u), iv = std::floor(v / cell_v);
  key = derive_key(derive_key(key, static_cast<std::uint64_t>(static_cast<std::int64_t>(iv))),
                   static_cast<std::uint64_t>(static_cast<std::int64_t>(iu)));
  const double scale = 0.6 + 0.8 * unit(key ^ 1u);
  const double half_w = std::min(0.5 * width * scale, 0.45 * cell_u),
               half_h = std::min(0.5 * height * scale, 0.45 * cell_v);
  const double cu = half_w + (cell_u - 2.0 * half_w) * unit(key ^ 2u);
  const double cv = half_h + (cell_v - 2.0 * half_h) * unit(key ^ 3u);
  const double du = (u - iu * cell_u - cu) / half_w, dv = (v - iv * cell_v - cv) / half_h;
  const double d = du * du + dv * dv;
  return static_cast<float>(std::clamp((1.0 - d) / 0.35, 0.0, 1.0));
}

}  // namespace

float mark_coverage(double along, double azimuth, double radius, float density, float width,
                    float height, unsigned salt) {
  if (density <= 0.0f || radius <= 0.0) return 0.0f;
  const double cell = 1.0 / std::sqrt(static_cast<double>(density));
  // Whole cells round the limb, so the pattern has no seam; their width is the circumference's
  // share, within a factor of 2 of `cell` except on limbs thinner than a cell.
  const double circumference = kTwoPi * radius;
  const double round_cells = std::max(1.0, std::round(circumference / cell));
  const double around = std::fmod(std::fmod(azimuth, kTwoPi) + kTwoPi, kTwoPi) * radius;
  return cell_mark(around, along, circumference / round_cells, cell,
                   derive_key(salt, static_cast<std::uint64_t>(round_cells)), width, height);
}

float mark_coverage_plane(double x, double y, float density, float width, float height,
                          unsigned salt) {
  if (density <= 0.0f) return 0.0f;
  const double cell = 1.0 / std::sqrt(static_cast<double>(density));
  return cell_mark(x, y, cell, cell, derive_key(salt, 0x706c616eull), width, height);
}

float BarkPattern::base(float z) const {
  if (base_height <= 0.0f) return 0.0f;
  const float t = std::clamp(1.0f - z / base_height, 0.0f, 1.0f);
  return t * t;
}

glm::vec3 BarkPattern::albedo(const glm::vec3& ridge, double height, double along, double azimuth,
                              double radius, float z) const {
  const float b = base(z);
  // The base: the bark darkens towards half the furrows' albedo (without furrows of its own, the
  // scene gives half the bark's albedo for them), and the furrows widen.
  const glm::vec3 dark = 0.5f * furrow_albedo;
  const glm::vec3 furrow = glm::mix(furrows ? furrow_albedo : ridge, dark, 0.85f * b);
  const glm::vec3 top = glm::mix(ridge, dark, 0.85f * b);
  // The procedural height's 10th, 50th and 90th percentiles are 0.63, 0.79 and 0.91.
  const float lo = 0.62f + 0.1f * b, hi = 0.86f + 0.06f * b;
  glm::vec3 a = glm::mix(furrow, top, smoothstep(lo, hi, static_cast<float>(height)));
  // Lenticels: dashes across the limb, 3–15 mm × 1–3 mm.
  a = glm::mix(a, lenticel_albedo,
               mark_coverage(along, azimuth, radius, lenticels, 0.009f, 0.0018f, 0x6c656eu));
  if (radius > 0.03) {
    // Scars: eyes 4–8 cm wide where branches fell.
    a = glm::mix(a, scar_albedo,
                 mark_coverage(along, azimuth, radius, scars, 0.06f, 0.02f, 0x736361u));
  }
  return a;
}

}  // namespace arbor::materials
