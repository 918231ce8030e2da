// Ünal 1995: recursive fractal trees, refined and time-aware.
#include "generator/models/fractal/fractal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "common/frame.h"
#include "common/rng.h"
#include "generator/grow_options.h"

namespace arbor::generator {

namespace {

// One random stream per stochastic parameter (§4.1), derived from the branch's identity, so the
// tree at t and at t + dt is the same tree, grown.
enum Stream : std::uint64_t {
  kLength = 1,
  kAngle,
  kAzimuth,
  kPrune,
  kWiggle,
  kRadius,
  kChild = 1000
};

class Grower {
  struct OpenStem {
    Stem stem;
    std::vector<SkeletonPoint> points;
    double length = 0.0;
  };

 public:
  Grower(const FractalParams& p, const FractalOptions& o, double age) : p_(p), o_(o), age_(age) {}

  Skeleton run() {
    const int levels =
        std::min(p_.depth, static_cast<int>(std::floor(age_ / p_.years_per_level)) + 1);
    levels_ = std::max(1, levels);
    Frame trunk;  // heading +z
    branch(0, -1, Vec3(0.0), trunk, p_.length, p_.radius, derive_key(o_.seed, 7));
    finish();
    return std::move(sk_);
  }

 private:
  double growth(int level) const {
    return fractal_growth(age_ - level * p_.years_per_level, p_.years_per_level);
  }

  // Grows one branch of `level` from `base` along frame.z (full-size length and radius), then its
  // children on the cone at its tip.
  void branch(int level, int parent, const Vec3& base, const Frame& frame, double full_length,
              double full_bottom_radius, std::uint64_t key) {
    const double s = growth(level);
    if (s <= 0.0) return;
    refuse_growth(o_.force, static_cast<double>(stems_.size()), o_.max_stems,
                  "the fractal tree grew past", "branches");
    Rng length_rng(derive_key(key, kLength)), wiggle_rng(derive_key(key, kWiggle)),
        radius_rng(derive_key(key, kRadius));
    const double length = full_length * length_rng.vary(1.0, p_.length_variation) * s;
    const double bottom = full_bottom_radius * s;
    const double top = bottom * p_.taper;
    OpenStem st;
    st.stem.parent = parent;
    st.stem.level = level;
    st.stem.taper = -1.0f;
    if (parent >= 0) {
      st.stem.parent_point =
          static_cast<std::int32_t>(stems_[static_cast<size_t>(parent)].points.size()) - 1;
      st.stem.parent_offset = static_cast<float>(stems_[static_cast<size_t>(parent)].length);
    }
    for (int d = 0; d < p_.discs; ++d) {
      const double f = static_cast<double>(d) / (p_.discs - 1);
      Vec3 centre = base + frame.z * (f * length);
      double r = bottom + (top - bottom) * f;
      if (d > 0) {
        // §3.2 refined model: disc centres shifted ⟂ the axis (only there, §4.1.1), radii varied.
        centre += frame.x * (wiggle_rng.symmetric() * p_.wiggle * length) +
                  frame.y * (wiggle_rng.symmetric() * p_.wiggle * length);
        r *= radius_rng.vary(1.0, p_.radius_variation);
      }
      st.points.push_back({glm::vec3(centre), static_cast<float>(std::max(0.0, r))});
    }
    // Keep radii from growing along the branch or past the parent's at the joint.
    if (parent >= 0) {
      st.points[0].radius =
          std::min(st.points[0].radius, stems_[static_cast<size_t>(parent)].points.back().radius);
    }
    for (std::size_t d = 1; d < st.points.size(); ++d) {
      st.points[d].radius = std::min(st.points[d].radius, st.points[d - 1].radius);
    }
    st.length = length;
    const int index = static_cast<int>(stems_.size());
    const Vec3 tip(st.points.back().position);
    stems_.push_back(std::move(st));
    if (level + 1 >= levels_) return;

    // §3.1: children on a cone whose tip is this branch's tip; §3.3: the cone widens as they grow.
    Rng angle_rng(derive_key(key, kAngle)), azimuth_rng(derive_key(key, kAzimuth)),
        prune_rng(derive_key(key, kPrune));
    const double child_growth = growth(level + 1);
    const double half_angle = 0.5 * p_.cone_angle * (1.0 - p_.cone_widening * (1.0 - child_growth));
    const Vec3 axis = glm::normalize(
        tip - Vec3(stems_[static_cast<size_t>(index)].points[p_.discs - 2].position));
    Frame at_tip = frame;
    at_tip.z = axis;
    at_tip = at_tip.orthonormalized();
    for (int c = 0; c < p_.branches; ++c) {
      // Draw every stream value whether or not the child survives, so pruning one child never
      // changes another.
      const double spread = angle_rng.vary(1.0, p_.angle_variation);
      const double azimuth = radians(p_.twist * level + 360.0 * c / p_.branches) +
                             azimuth_rng.symmetric() * p_.angle_variation * kPi / p_.branches;
      const bool pruned = prune_rng.uniform() < p_.prune;  // §3.2: its descendants go with it
      if (pruned) continue;
      const Frame child = at_tip.rotated_z(azimuth).rotated_x(radians(half_angle * spread));
      branch(level + 1, index, tip, child, full_length * p_.size_ratio,
             full_bottom_radius * p_.taper,
             derive_key(key, kChild + static_cast<std::uint64_t>(c)));
    }
  }

  void finish() {
    std::vector<bool> has_children(stems_.size(), false);
    for (const OpenStem& s : stems_) {
      if (s.stem.parent >= 0) has_children[static_cast<size_t>(s.stem.parent)] = true;
    }
    for (std::size_t i = 0; i < stems_.size(); ++i) {
      OpenStem& s = stems_[i];
      Stem st = s.stem;
      st.first_point = static_cast<std::uint32_t>(sk_.points.size());
      st.point_count = static_cast<std::uint32_t>(s.points.size());
      st.length = static_cast<float>(s.length);
      st.base_radius = s.points.front().radius;
      sk_.points.insert(sk_.points.end(), s.points.begin(), s.points.end());
      sk_.stems.push_back(st);
      if (!has_children[i] && p_.leaves > 0) add_leaves(static_cast<int>(i), s);
    }
    int levels = 1;
    for (const Stem& s : sk_.stems) levels = std::max(levels, s.level + 1);
    sk_.levels = levels;
  }

  // Leaves along the outer half of an outermost branch, spiralling round it and leaning out.
  void add_leaves(int stem, const OpenStem& s) {
    const glm::dvec3 a(s.points.front().position), b(s.points.back().position);
    const glm::dvec3 h = glm::normalize(b - a);
    const glm::dvec3 side = any_perpendicular(h);
    const double g = growth(s.stem.level);
    for (int k = 0; k < p_.leaves; ++k) {
      const double f = 0.5 + 0.5 * (k + 0.5) / p_.leaves;
      const glm::dvec3 out = rotate(side, h, radians(137.5 * k));
      Leaf leaf;
      leaf.position = glm::vec3(a + (b - a) * f);
      leaf.axis = glm::vec3(glm::normalize(h + out));
      leaf.normal =
          glm::vec3(glm::normalize(glm::cross(glm::dvec3(leaf.axis), glm::cross(out, h))));
      leaf.length = static_cast<float>(p_.leaf_length * g);
      leaf.width = static_cast<float>(p_.leaf_width * g);
      leaf.stem = stem;
      leaf.shape = p_.leaf_shape;
      if (leaf.length > 0.0f) sk_.leaves.push_back(leaf);
    }
  }

  static Vec3 any_perpendicular(const Vec3& v) {
    const Vec3 a = std::fabs(v.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    return glm::normalize(glm::cross(a, v));
  }

  const FractalParams& p_;
  const FractalOptions& o_;
  double age_;
  int levels_ = 1;
  std::vector<OpenStem> stems_;
  Skeleton sk_;
};

}  // namespace

double fractal_growth(double age, double n) {
  if (age <= 0.0) return 0.0;
  if (age <= 0.5 * n) return age / n;
  return 1.0 - n / (4.0 * age);
}

double fractal_full_age(const FractalParams& p) {
  return (p.depth - 1) * p.years_per_level + 4.0 * p.years_per_level;
}

double fractal_estimate(const FractalParams& p) {
  double total = 0.0, level = 1.0;
  for (int d = 0; d < p.depth; ++d) {
    total += level;
    level *= p.branches;
  }
  return total;
}

Skeleton grow_fractal(const FractalParams& p, const FractalOptions& o) {
  const double estimate = fractal_estimate(p);
  refuse_estimate(o.force, estimate, o.max_stems, "the fractal tree would have", "branches");
  const double age = o.time > 0.0 ? o.time : (p.age > 0.0 ? p.age : fractal_full_age(p));
  return Grower(p, o, age).run();
}

}  // namespace arbor::generator
