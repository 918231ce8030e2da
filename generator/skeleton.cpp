// Skeleton queries and invariant checks.
#include "generator/skeleton.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "generator/models/weber_penn/weber_penn_formulas.h"

namespace arbor::generator {

float Skeleton::radius_at(const Stem& s, double z) const {
  if (s.taper >= 0.0f) {
    return static_cast<float>(wp::taper_radius(s.taper, s.base_radius, s.length, z));
  }
  // No taper law: interpolate the point radii linearly in z over the stem's points.
  const double z0 = s.z_start;
  const double t = (z - z0) / std::max(1e-9, 1.0 - z0) * (s.point_count - 1);
  const auto i = static_cast<std::uint32_t>(std::clamp(std::floor(t), 0.0, s.point_count - 2.0));
  const double f = std::clamp(t - i, 0.0, 1.0);
  const SkeletonPoint& a = points[s.first_point + i];
  const SkeletonPoint& b = points[s.first_point + i + 1];
  return static_cast<float>(a.radius + (b.radius - a.radius) * f);
}

glm::vec3 Skeleton::position_at_offset(const Stem& s, double offset) const {
  // Walk the polyline from the stem's first point; offsets are measured from the base of the
  // whole (unsplit) stem, so a clone starts at z_start * length.
  double remaining = offset - s.z_start * s.length;
  for (std::uint32_t i = 0; i + 1 < s.point_count; ++i) {
    const glm::vec3 a = points[s.first_point + i].position;
    const glm::vec3 b = points[s.first_point + i + 1].position;
    const double len = glm::length(b - a);
    if (remaining <= len || i + 2 == s.point_count) {
      const float f = len > 0.0 ? static_cast<float>(std::clamp(remaining / len, 0.0, 1.0)) : 0.f;
      return a + (b - a) * f;
    }
    remaining -= len;
  }
  return points[s.first_point].position;
}

std::size_t Skeleton::leaf_count() const {
  std::int32_t free = -1;
  for (const LeafTriangle& t : leaf_triangles) free = std::max(free, t.leaf);
  for (const LeafLine& l : leaf_lines) free = std::max(free, l.leaf);
  return leaves.size() + static_cast<std::size_t>(free + 1);
}

std::string scale_problem(const Skeleton& sk) {
  constexpr float kReach = 1e6f;  // metres
  auto outside = [](const glm::vec3& p) {
    return !(std::fabs(p.x) <= kReach && std::fabs(p.y) <= kReach && std::fabs(p.z) <= kReach);
  };
  for (const SkeletonPoint& p : sk.points) {
    if (outside(p.position) || !(p.radius <= kReach))
      return "a limb point lies beyond 1000 km (or is not finite)";
  }
  for (std::size_t i = 0; i < sk.stems.size(); ++i) {
    const Stem& s = sk.stems[i];
    for (std::uint32_t k = 1; k < s.point_count; ++k) {
      const float d = glm::length(sk.points[s.first_point + k].position -
                                  sk.points[s.first_point + k - 1].position);
      if (!(d >= 1e-6f)) {
        return "stem " + std::to_string(i) + " (level " + std::to_string(s.level) +
               ") has a segment shorter than 1 micrometre";
      }
    }
  }
  for (const Leaf& l : sk.leaves) {
    if (outside(l.position) || !(l.length <= kReach && l.width <= kReach)) {
      return "a leaf lies beyond 1000 km or is larger (or is not finite)";
    }
  }
  for (const LeafTriangle& t : sk.leaf_triangles) {
    for (const glm::vec3& v : t.v) {
      if (outside(v)) return "a leaf triangle lies beyond 1000 km (or is not finite)";
    }
  }
  for (const LeafLine& l : sk.leaf_lines) {
    if (outside(l.a) || outside(l.b) || !(l.radius <= kReach))
      return "a leaf line lies beyond 1000 km (or is not finite)";
  }
  return "";
}

std::string validate(const Skeleton& sk) {
  int roots = 0;
  for (size_t i = 0; i < sk.stems.size(); ++i) {
    const Stem& s = sk.stems[i];
    // Named only when something is wrong: formatting it for each of the willow's 50,000 valid
    // stems was a tenth of validating its skeleton.
    const auto name = [i] { return "stem " + std::to_string(i); };
    if (s.parent < 0) {
      ++roots;
    } else if (static_cast<size_t>(s.parent) >= i) {
      return name() + " has parent " + std::to_string(s.parent) +
             ", not an earlier stem (a cycle or a forward link)";
    }
    if (s.point_count < 2) return name() + " has fewer than two points";
    if (static_cast<size_t>(s.first_point) + s.point_count > sk.points.size()) {
      return name() + " refers to points past the end";
    }
    for (std::uint32_t k = 0; k < s.point_count; ++k) {
      const SkeletonPoint& p = sk.points[s.first_point + k];
      if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) ||
          !std::isfinite(p.position.z) || !std::isfinite(p.radius)) {
        return name() + " has a point that is not finite";
      }
      if (p.radius < 0.0f) return name() + " has a negative radius";
    }
    if (s.parent >= 0) {
      const Stem& parent = sk.stems[static_cast<size_t>(s.parent)];
      if (s.parent_point >= static_cast<std::int32_t>(parent.point_count)) {
        return name() + " starts at point " + std::to_string(s.parent_point) +
               " of its parent, which has only " + std::to_string(parent.point_count);
      }
      const double z = parent.length > 0.0f ? s.parent_offset / parent.length : 0.0;
      const float parent_radius =
          s.parent_point >= 0
              ? sk.points[parent.first_point + static_cast<std::uint32_t>(s.parent_point)].radius
              : sk.radius_at(parent, std::clamp(z, 0.0, 1.0));
      const float own = sk.points[s.first_point].radius;
      if (own > parent_radius * 1.0001f + 1e-7f) {
        return name() + " starts with radius " + std::to_string(own) +
               " thicker than its parent there (" + std::to_string(parent_radius) + ")";
      }
    }
  }
  if (!sk.stems.empty() && roots != 1) {
    return "the skeleton has " + std::to_string(roots) + " roots; it must have exactly one";
  }
  for (size_t i = 0; i < sk.leaves.size(); ++i) {
    const Leaf& l = sk.leaves[i];
    if (l.stem < 0 || static_cast<size_t>(l.stem) >= sk.stems.size()) {
      return "leaf " + std::to_string(i) + " is on no stem";
    }
  }
  return "";
}

}  // namespace arbor::generator
