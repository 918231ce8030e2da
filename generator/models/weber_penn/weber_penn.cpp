// Weber & Penn 1995 §4: stems grown segment by segment with curvature, splits (clones), children,
// leaves, pruning, vertical attraction and wind sway. Paper equations live in
// weber_penn_formulas.cpp; this file is the recursive construction that applies them.
#include "generator/models/weber_penn/weber_penn.h"

#include <algorithm>
#include <array>
#include <deque>
#include <cmath>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/frame.h"
#include "common/progress.h"
#include "common/rng.h"
#include "generator/models/weber_penn/weber_penn_formulas.h"
#include "generator/models/weber_penn/weber_penn_leaves.h"

namespace arbor::generator {

namespace {

// Labels of the independent random streams. A stem's streams derive from its own key, and a
// child's key from its parent's key and its ordinal, so changing one parameter only reshuffles
// the draws that depend on it.
enum Stream : std::uint64_t {
  kTreeScale = 1,
  kTrunk,
  kCurve,
  kSplit,
  kChildPlacement,
  kLeafPlacement,
  kLength,
  kDown,
  kSway,
  kChildBase = 1u << 20,
  kCloneBase = 1u << 30,
};

constexpr double kMinLength = 1e-4;  // metres; shorter stems are not grown
const Vec3 kUp{0.0, 0.0, 1.0};

// An angle (radians) less the nearest whole number of turns: within [−π, π] to a few ulp, for
// angles accumulated over many placements before they go to single precision.
inline double turns_reduced(double angle) {
  if (std::fabs(angle) < kPi) return angle;  // what the reduction below gives, without a division
  const double turns = angle / (2.0 * kPi);
  return angle -
         2.0 * kPi *
             static_cast<double>(static_cast<std::int64_t>(turns + std::copysign(0.5, turns)));
}

// Counts a level of recursion for as long as it lives.
struct DepthGuard {
  explicit DepthGuard(std::size_t& depth) : depth_(depth) { ++depth_; }
  ~DepthGuard() { --depth_; }
  DepthGuard(const DepthGuard&) = delete;
  DepthGuard& operator=(const DepthGuard&) = delete;
  std::size_t& depth_;
};

// Where a child starts on its parent and the parent's frame there, turned to the child's azimuth.
struct Place {
  Vec3 at;
  Frame turned;
};

// Azimuth state for placing children or leaves about a stem (§4.3 nRotate).
struct Placement {
  double azimuth = 0.0;  // degrees, accumulated for the helical mode
  double side = 1.0;     // alternating mode: which side the next child goes
  double carry = 0.0;    // error diffusion of fractional counts per segment
};

// Where a stem starts, which way it grows, and the §4.2 back-rotation it carries.
struct Pose {
  Frame frame;
  Vec3 position{0.0};
  double split_correction = 0.0;    // radians per remaining segment (§4.2 back-rotation)
  double pending_correction = 0.0;  // joins split_correction after the next segment
};

// Everything needed to grow one stem (or clone).
struct StemSpec {
  int level = 0;
  int parent = -1;
  bool is_clone = false;
  double parent_offset = 0.0;
  Pose pose;
  // With wind and pruning, the pose of the same stem in the tree at rest, which the pruning
  // envelope is tested against (§4.7: "the same basic geometry, perturbed only by the wind").
  Pose rest;
  double length = 0.0;
  double base_radius = 0.0;
  int first_segment = 0;
  int parent_first_segment = 0;  // for clones: the first segment of the stem they split from
  std::uint64_t key = 0;
  double share = 1.0;     // fraction of the children/leaves this clone carries
  double children = 0.0;  // children over the whole stem (before sharing)
  double leaves = 0.0;    // leaves over the whole stem (before sharing)
  Placement child_place;
  Placement leaf_place;
  // Where the stem grows from, to recompute radius and counts when pruning shortens it.
  double parent_length = 0.0;
  double parent_base_radius = 0.0;
  double parent_radius_here = 0.0;
  double length_max = 0.0;
};

class Grower {
 public:
  Grower(const WeberPennParams& p, const GrowOptions& o, Skeleton& out) : p_(p), o_(o), out_(out) {
    env_.width_peak = p.prune_width_peak;
    env_.power_low = p.prune_power_low;
    env_.power_high = p.prune_power_high;
    Rng tree(derive_key(o.seed, kTreeScale));
    scale_tree_ = tree.vary(p.scale, p.scale_v);
    z_scale_ = tree.vary(p.z_scale, p.z_scale_v);
    base_length_ = p.base_size * scale_tree_;
    leaf_scale_ = 1.0 / std::sqrt(o.quality);
    wind_ = p.wind_speed != 0.0 || p.wind_gust != 0.0;
    at_rest_too_ = wind_ && p.prune_ratio > 0.0;
  }

  void grow() {
    const WeberPennLevel& l0 = p_.level[0];
    Rng trunk(derive_key(o_.seed, kTrunk));
    StemSpec s;
    s.key = derive_key(o_.seed, kTrunk + 1000);
    s.length = std::max(0.0, trunk.vary(l0.length, l0.length_v)) * scale_tree_;
    trunk_length_ = s.length;
    // §4.4: radius_trunk = length_trunk * Ratio * (0Scale ± 0ScaleV).
    s.base_radius = s.length * p_.ratio * trunk.vary(l0.scale, l0.scale_v);
    s.children = p_.levels > 1 ? std::fabs(p_.at(1).branches) : 0.0;
    s.leaves = p_.levels == 1 ? leaf_count(0.0, 0.0) : 0.0;
    s.child_place.azimuth = Rng(derive_key(s.key, kChildPlacement)).uniform() * 360.0;
    s.leaf_place.azimuth = Rng(derive_key(s.key, kLeafPlacement)).uniform() * 360.0;
    grow_stem(s);
    orienter_.flush();
    apply_z_scale();
    out_.trunk.flare = static_cast<float>(p_.flare);
    out_.trunk.lobes = p_.lobes;
    out_.trunk.lobe_depth = static_cast<float>(p_.lobe_depth);
  }

 private:
  double base_offset(const StemSpec& s) const { return s.level == 0 ? base_length_ : 0.0; }

  // Stem radius at normalised z (without flare, which is displacement of the trunk surface).
  double radius_at(const StemSpec& s, double z) const {
    return wp::taper_radius(p_.at(s.level).taper, s.base_radius, s.length, z);
  }

  // §4.4 child radius and §4.3/§4.5 counts, all functions of the stem's (possibly pruned) length.
  void size_stem(StemSpec& s) const {
    s.base_radius = s.parent_base_radius * std::pow(s.length / s.parent_length, p_.ratio_power);
    s.base_radius = std::min(s.base_radius, s.parent_radius_here);
    const int next = s.level + 1;
    s.children = 0.0;
    if (next < p_.levels) {
      const double stems_max = std::fabs(p_.at(next).branches);
      s.children =
          s.level == 1
              ? wp::children_of_first_level(stems_max, s.length, s.parent_length, s.length_max)
              : wp::children_of_deeper_level(stems_max, s.parent_offset, s.parent_length);
    }
    s.leaves = next == p_.levels ? leaf_count(s.parent_offset, s.parent_length) : 0.0;
    // A fan (negative nBranches) holds exactly |nBranches| children at the tip.
    if (next < p_.levels && p_.at(next).branches < 0.0) s.children = -p_.at(next).branches;
  }

  // §4.5 leaves on a stem; a fan (negative Leaves) holds exactly |Leaves| · quality at the tip.
  double leaf_count(double offset, double parent_length) const {
    if (p_.leaves < 0.0) return -p_.leaves * o_.quality;
    return wp::leaves_per_branch(p_.leaves, offset, parent_length, o_.quality);
  }

  // §4.6: probe the stem and its clones; shorten until inside, then blend by PruneRatio. With
  // wind the probe grows from the stem's pose at rest, so that the sway bends the same branches at
  // every time instead of pruning different ones.
  void prune(StemSpec& s) {
    const double original = s.length;
    double length = original;
    bool fits = false;
    for (int iteration = 0; iteration < 64 && length > kMinLength; ++iteration) {
      StemSpec probe = s;
      if (at_rest_too_) probe.pose = s.rest;
      probe.length = length;
      const SplitErrors saved = split_error_;
      fits = trace(probe, true);
      split_error_ = saved;
      if (fits) break;
      length *= 0.9;
    }
    if (!fits) length = 0.0;
    s.length = original + p_.prune_ratio * (length - original);
    size_stem(s);
  }

  void grow_stem(StemSpec s) {
    if (p_.prune_ratio > 0.0 && s.level >= 1) prune(s);
    if (s.length < kMinLength || s.base_radius <= 0.0) return;
    trace(s, false);
  }

  // §4.1 curvature of segment i (degrees), its random part drawn from curve_rng.
  double curvature_step(const WeberPennLevel& lv, int i, Rng& curve_rng) const {
    const int n = lv.curve_res;
    double delta = 0.0;
    if (lv.curve_back == 0.0) {
      delta = lv.curve / n;
    } else {
      // A segment is in the first half when i < CurveRes / 2 (real division).
      delta = (i < n / 2.0 ? lv.curve : lv.curve_back) / (n / 2.0);
    }
    if (lv.curve_v > 0.0) delta += lv.curve_v / n * curve_rng.symmetric();
    return delta;
  }

  // Frame of segment i: curvature `delta` (§4.1), attraction (§4.8), split back-rotation (§4.2)
  // and, when `sway`, the wind (§4.7) turn the previous segment's frame. The first segment keeps
  // the stem's frame.
  Frame bend(const StemSpec& s, Frame f, int i, double delta, double split_correction,
             const double sway_offset[2], bool sway) const {
    const int n = p_.at(s.level).curve_res;
    f = f.rotated_x(radians(delta));
    if (s.level >= 2 && p_.attraction_up != 0.0) {
      // §4.8; the rotation sign is chosen so that positive AttractionUp curves stems upward,
      // as the text describes (a positive x-rotation turns z toward -y, i.e. down).
      f = f.rotated_x(-wp::attraction_up(p_.attraction_up, f.z.z, f.y.z, n));
    }
    if (split_correction != 0.0) f = f.rotated_x(-split_correction);
    if (sway) {
      const double z = static_cast<double>(i) / n;
      const wp::Sway sw =
          wp::sway_angles(p_.wind_speed, p_.wind_gust, s.length, s.base_radius, radius_at(s, z), z,
                          n, o_.time, sway_offset[0], sway_offset[1]);
      f = f.rotated_x(radians(sw.x)).rotated_y(radians(sw.y));
    }
    return f.orthonormalized();
  }

  // Azimuth (degrees) of the next child or leaf about its parent (§4.3 nRotate).
  static double next_azimuth(Placement& pl, const WeberPennLevel& lv, Rng& rng) {
    if (lv.rotate >= 0.0) {
      pl.azimuth += rng.vary(lv.rotate, lv.rotate_v);
      return pl.azimuth;
    }
    // Negative nRotate: (180 + nRotate ± nRotateV) on alternating sides of the parent's y axis.
    pl.side = -pl.side;
    return pl.side * (180.0 + lv.rotate + lv.rotate_v * rng.symmetric());
  }

  double down_angle(const WeberPennLevel& lv, Rng& rng, const StemSpec& parent,
                    double offset) const {
    if (lv.down_angle_v >= 0.0) return rng.vary(lv.down_angle, lv.down_angle_v);
    return wp::down_angle_along_parent(lv.down_angle, lv.down_angle_v, parent.length, offset,
                                       base_offset(parent));
  }

  // Error-diffused integer count for an expected fractional count.
  static int diffuse(double& carry, double expected) {
    const int count = static_cast<int>(std::floor(expected + carry + 0.5));
    carry += expected - count;
    return std::max(0, count);
  }

  // Grows a child of `parent` at `offset` metres along it. `here.turned` is the parent's frame
  // there, already turned about the parent's axis (azimuth) or across it (fan); the child's own
  // down angle is applied here. `at_rest` is the same place in the tree at rest (see prune).
  void spawn_child(const StemSpec& parent, int stem_index, double offset, const Place& here,
                   const Place& at_rest, std::uint64_t ordinal) {
    const int level = parent.level + 1;
    const WeberPennLevel& lv = p_.at(level);
    StemSpec c;
    c.level = level;
    c.parent = stem_index;
    c.parent_offset = offset;
    c.key = derive_key(parent.key, kChildBase + ordinal);
    Rng own_length(derive_key(c.key, kLength));
    Rng own_down(derive_key(c.key, kDown));
    c.length_max = std::max(0.0, own_length.vary(lv.length, lv.length_v));
    c.length = level == 1 ? wp::first_level_length(p_.shape, parent.length, c.length_max, offset,
                                                   base_length_, env_)
                          : wp::deeper_level_length(c.length_max, parent.length, offset);
    if (c.length < kMinLength) return;
    c.parent_length = parent.length;
    c.parent_base_radius = parent.base_radius;
    c.parent_radius_here = radius_at(parent, offset / parent.length);
    const double down = down_angle(lv, own_down, parent, offset);
    c.pose.frame = here.turned.rotated_x(radians(down));
    c.pose.position = here.at;
    if (at_rest_too_) {
      c.rest.frame = at_rest.turned.rotated_x(radians(down));
      c.rest.position = at_rest.at;
    }
    size_stem(c);
    c.child_place.azimuth = Rng(derive_key(c.key, kChildPlacement)).uniform() * 360.0;
    c.leaf_place.azimuth = Rng(derive_key(c.key, kLeafPlacement)).uniform() * 360.0;
    grow_stem(c);
  }

  // A leaf at `at`, turned by `azimuth` (radians) about the frame's z axis and then by its down
  // angle about the turned x axis (§4.5), oriented toward the light (§4.9) by orienter_.
  void add_leaf(const StemSpec& s, int stem_index, double offset, const Vec3& at, const Frame& base,
                double azimuth, Rng& rng) {
    const WeberPennLevel& lv = p_.at(p_.levels);
    const double down = radians(down_angle(lv, rng, s, offset));
    Leaf leaf;
    leaf.position = glm::vec3(at);
    leaf.length = static_cast<float>(p_.leaf_scale * leaf_scale_);
    leaf.width = static_cast<float>(p_.leaf_scale * p_.leaf_scale_x * leaf_scale_);
    leaf.stem = stem_index;
    leaf.shape = p_.leaf_shape;
    out_.leaves.push_back(leaf);
    orienter_.add(glm::vec3(base.x), glm::vec3(base.y), glm::vec3(base.z),
                  static_cast<float>(turns_reduced(azimuth)),
                  static_cast<float>(turns_reduced(down)));
  }

  // Grows one stem segment by segment. In probe mode nothing is written and children are not
  // spawned; returns whether the stem and its clones stay inside the pruning envelope.
  bool trace(StemSpec s, bool probe) {
    const WeberPennLevel& lv = p_.at(s.level);
    const int n = lv.curve_res;
    const double seg_len = s.length / n;
    Rng curve_rng(derive_key(s.key, kCurve));
    Rng split_rng(derive_key(s.key, kSplit));
    Rng sway_rng(derive_key(s.key, kSway));
    const double sway_offset[2] = {sway_rng.uniform() * 2.0 * kPi, sway_rng.uniform() * 2.0 * kPi};
    const bool grows_leaves = !probe && s.level + 1 == p_.levels && p_.leaves != 0.0;
    const bool grows_children = !probe && s.level + 1 < p_.levels;
    const bool fan_children = p_.levels > s.level + 1 && p_.at(s.level + 1).branches < 0.0;
    const bool fan_leaves = p_.leaves < 0.0;
    const bool helix = lv.curve_v < 0.0;

    int stem_index = -1;
    if (point_buffers_.size() <= depth_) point_buffers_.emplace_back();
    std::vector<SkeletonPoint>& points = point_buffers_[depth_];
    points.clear();
    const DepthGuard guard(depth_);
    if (!probe) {
      stem_index = static_cast<int>(out_.stems.size());
      Stem st;
      st.level = s.level;
      st.parent = s.parent;
      st.is_clone = s.is_clone;
      st.parent_offset = static_cast<float>(s.parent_offset);
      if (s.is_clone) {
        // A clone starts at its twin's point at the split (twin's points begin at its own start).
        st.parent_point = s.first_segment - s.parent_first_segment;
      }
      st.length = static_cast<float>(s.length);
      st.base_radius = static_cast<float>(s.base_radius);
      st.z_start = static_cast<float>(static_cast<double>(s.first_segment) / n);
      st.taper = static_cast<float>(lv.taper);
      out_.stems.push_back(st);
      points.reserve(static_cast<size_t>(n - s.first_segment + 1));
      points.push_back({glm::vec3(s.pose.position), static_cast<float>(radius_at(s, st.z_start))});
      if (o_.progress && (out_.stems.size() & 1023u) == 0) o_.progress->update(out_.stems.size());
      refuse_growth(o_.force, static_cast<double>(out_.stems.size()), o_.max_stems,
                    "the tree grew past", "stems");
    }
    Rng child_rng(derive_key(s.key, kChildPlacement + 7));
    Rng leaf_rng(derive_key(s.key, kLeafPlacement + 7));
    std::uint64_t child_ordinal = static_cast<std::uint64_t>(s.first_segment) << 16;

    // With wind and pruning the tree at rest is walked beside the swaying one (`rest_*`): its
    // children and clones start where the tree at rest has them, for their pruning probes.
    const bool at_rest_too = at_rest_too_ && !probe;
    Frame axis = s.pose.frame, rest_axis = s.rest.frame;
    Vec3 pos = s.pose.position, rest_pos = s.rest.position;
    for (int i = s.first_segment; i < n; ++i) {
      if (i > 0) {
        const double delta = curvature_step(lv, i, curve_rng);
        axis = bend(s, axis, i, delta, s.pose.split_correction, sway_offset, wind_ && !probe);
        if (at_rest_too)
          rest_axis = bend(s, rest_axis, i, delta, s.rest.split_correction, sway_offset, false);
      }
      // The segment right after a split keeps the full split angle; the back-rotation starts
      // on the segment after it.
      for (Pose* pose : {&s.pose, &s.rest}) {
        pose->split_correction += pose->pending_correction;
        pose->pending_correction = 0.0;
      }
      Frame seg = axis, rest_seg = rest_axis;
      if (helix) {
        // §4.1 negative nCurveV: the segments wind about the stem's axis at |nCurveV| degrees,
        // one full turn over the stem (arbor's choice; the paper gives only the angle).
        seg = axis.rotated_z(2.0 * kPi * i / n).rotated_x(radians(-lv.curve_v));
        if (at_rest_too)
          rest_seg = rest_axis.rotated_z(2.0 * kPi * i / n).rotated_x(radians(-lv.curve_v));
      }
      const Vec3 end = pos + seg.z * seg_len;
      if (probe && !wp::inside_envelope(end.x, end.y, end.z, scale_tree_, p_.base_size,
                                        p_.prune_width, env_)) {
        return false;
      }
      // Children and leaves along this segment (§4.3, §4.5), evenly spaced, counts diffused.
      const double a = i * seg_len;
      const double lo = std::max(a, base_offset(s));
      const double usable = a + seg_len - lo;
      const double span = s.length - base_offset(s);
      if (grows_children && !fan_children && usable > 0.0 && span > 0.0) {
        const int count = diffuse(s.child_place.carry, s.children * s.share * usable / span);
        const WeberPennLevel& child_level = p_.at(s.level + 1);
        for (int k = 0; k < count; ++k) {
          const double off = lo + usable * (k + 0.5) / count;
          const double azimuth = next_azimuth(s.child_place, child_level, child_rng);
          const Place here{pos + seg.z * (off - a), seg.rotated_z(radians(azimuth))};
          const Place at_rest = at_rest_too ? Place{rest_pos + rest_seg.z * (off - a),
                                                    rest_seg.rotated_z(radians(azimuth))}
                                            : here;
          spawn_child(s, stem_index, off, here, at_rest, child_ordinal++);
        }
      }
      if (grows_leaves && !fan_leaves && usable > 0.0 && span > 0.0) {
        const int count = diffuse(s.leaf_place.carry, s.leaves * s.share * usable / span);
        for (int k = 0; k < count; ++k) {
          const double off = lo + usable * (k + 0.5) / count;
          const double azimuth = next_azimuth(s.leaf_place, p_.at(p_.levels), leaf_rng);
          add_leaf(s, stem_index, off, pos + seg.z * (off - a), seg, radians(azimuth), leaf_rng);
        }
      }
      pos = end;
      if (at_rest_too) rest_pos = rest_pos + rest_seg.z * seg_len;
      if (!probe) {
        points.push_back({glm::vec3(pos), static_cast<float>(radius_at(s, double(i + 1) / n))});
      }
      if (i + 1 < n) {
        if (!split(s, stem_index, i, axis, pos, rest_axis, rest_pos, split_rng, probe))
          return false;
      }
    }
    // Fans at the tip (§4.5 negative Leaves; negative nBranches likewise).
    if (grows_leaves && fan_leaves) {
      const int count = diffuse(s.leaf_place.carry, s.leaves);
      const double spread = p_.at(p_.levels).rotate;
      for (int k = 0; k < count; ++k) {
        const double angle = -0.5 * spread + spread * (k + 0.5) / count;
        add_leaf(s, stem_index, s.length, pos, axis.rotated_y(radians(angle)), 0.0, leaf_rng);
      }
    }
    if (grows_children && fan_children) {
      const int count = diffuse(s.child_place.carry, s.children);
      const double spread = p_.at(s.level + 1).rotate;
      for (int k = 0; k < count; ++k) {
        const double angle = -0.5 * spread + spread * (k + 0.5) / count;
        const Place here{pos, axis.rotated_y(radians(angle))};
        const Place at_rest =
            at_rest_too ? Place{rest_pos, rest_axis.rotated_y(radians(angle))} : here;
        spawn_child(s, stem_index, s.length, here, at_rest, child_ordinal++);
      }
    }
    if (!probe) {
      Stem& st = out_.stems[static_cast<size_t>(stem_index)];
      st.first_point = static_cast<std::uint32_t>(out_.points.size());
      st.point_count = static_cast<std::uint32_t>(points.size());
      out_.points.insert(out_.points.end(), points.begin(), points.end());
    }
    return true;
  }

  // §4.2 splits at the end of segment i: the stem and its clones turn away by angle_split and
  // spread about the tree-parallel axis. Clones are grown at once. Returns false when a probed
  // clone leaves the envelope.
  bool split(StemSpec& s, int stem_index, int i, Frame& axis, const Vec3& pos, Frame& rest_axis,
             const Vec3& rest_pos, Rng& split_rng, bool probe) {
    const WeberPennLevel& lv = p_.at(s.level);
    const int n = lv.curve_res;
    int clones = 0;
    if (s.level == 0 && i == 0 && !s.is_clone && lv.base_splits > 0) {
      clones = lv.base_splits;  // 0BaseSplits replaces nSegSplits after the trunk's first segment
    } else if (lv.seg_splits > 0.0) {
      clones = split_error_[static_cast<size_t>(s.level)].next(lv.seg_splits);
    }
    if (clones == 0) return true;

    const double sampled_angle = split_rng.vary(lv.split_angle, lv.split_angle_v);
    const double spread_draw = split_rng.uniform();
    const double sign = split_rng.uniform() < 0.5 ? -1.0 : 1.0;
    const int remaining = n - (i + 2);  // segments after the first one past the split
    const double share = s.share / (clones + 1);
    // The split turns a stem by an angle that depends on its declination: the tree at rest's
    // stems turn by their own.
    struct Turn {
      double angle, spread, correction;
    };
    auto turn_of = [&](const Frame& f) {
      const double declination = degrees(std::acos(std::clamp(f.z.z, -1.0, 1.0)));
      const double angle = wp::split_angle(sampled_angle, declination);
      return Turn{angle, wp::split_spread(declination, spread_draw),
                  remaining > 0 ? radians(angle) / remaining : 0.0};
    };
    const bool at_rest_too = at_rest_too_ && !probe;
    const Turn turn = turn_of(axis), rest_turn = at_rest_too ? turn_of(rest_axis) : turn;
    // One clone: the paper rotates only the original (by ±spread). Several clones (the paper is
    // silent): all stems are set evenly around the axis, the original at ±spread.
    auto clone_frame = [&](const Frame& f, const Turn& t, int j) {
      const double azimuth = clones == 1 ? 0.0 : sign * t.spread + j * 360.0 / (clones + 1);
      return f.rotated_x(radians(t.angle)).rotated_about(kUp, radians(azimuth));
    };
    for (int j = 1; j <= clones; ++j) {
      StemSpec c = s;
      c.is_clone = true;
      c.parent = stem_index;
      c.parent_offset = (i + 1) * (s.length / n);
      c.first_segment = i + 1;
      c.parent_first_segment = s.first_segment;
      c.key = derive_key(s.key, kCloneBase + static_cast<std::uint64_t>(i + 1) * 64 + j);
      c.pose.position = pos;
      c.pose.frame = clone_frame(axis, turn, j);
      c.pose.pending_correction = turn.correction;
      if (at_rest_too) {
        c.rest.position = rest_pos;
        c.rest.frame = clone_frame(rest_axis, rest_turn, j);
        c.rest.pending_correction = rest_turn.correction;
      }
      c.share = share;
      // Clones share their twin's length: not pruned separately (the twin's probe covered them).
      if (!trace(c, probe) && probe) return false;
    }
    axis = axis.rotated_x(radians(turn.angle)).rotated_about(kUp, radians(sign * turn.spread));
    s.pose.pending_correction = turn.correction;
    if (at_rest_too) {
      rest_axis = rest_axis.rotated_x(radians(rest_turn.angle))
                      .rotated_about(kUp, radians(sign * rest_turn.spread));
      s.rest.pending_correction = rest_turn.correction;
    }
    s.share = share;
    return true;
  }

  void apply_z_scale() {
    if (z_scale_ == 1.0) return;
    const float zs = static_cast<float>(z_scale_);
    for (SkeletonPoint& p : out_.points) p.position.z *= zs;
    for (Leaf& l : out_.leaves) {
      l.position.z *= zs;
      l.axis.z *= zs;
      l.normal.z /= zs;
      l.axis = glm::normalize(l.axis);
      l.normal = glm::normalize(l.normal - glm::dot(l.normal, l.axis) * l.axis);
    }
  }

  const WeberPennParams& p_;
  const GrowOptions& o_;
  Skeleton& out_;
  wp::Envelope env_;
  double scale_tree_ = 0.0, z_scale_ = 1.0, base_length_ = 0.0, trunk_length_ = 0.0;
  double leaf_scale_ = 1.0;
  bool wind_ = false;
  bool at_rest_too_ = false;  // wind and pruning: the tree at rest is walked too (prune)
  // The split error diffusion per level (Levels ≤ 9), copied for every pruning probe.
  using SplitErrors = std::array<wp::SplitDiffusion, 10>;
  SplitErrors split_error_{};
  // Point buffers for the stems being traced, one per depth of trace's recursion (a stem's
  // points are appended to the skeleton only when its children are done): reused, not allocated
  // for each of the willow's 50,000 stems.
  std::deque<std::vector<SkeletonPoint>> point_buffers_;
  std::size_t depth_ = 0;
  // Orients the leaves a block at a time as they are placed.
  wp::LeafOrienter orienter_{static_cast<float>(p_.leaf_bend), out_.leaves};
};

}  // namespace

Skeleton grow_weber_penn(const WeberPennParams& params, const GrowOptions& options) {
  const SizeEstimate estimate = estimate_size(params, options.quality);
  if (!options.force &&
      (estimate.stems > options.max_stems || estimate.leaves > options.max_leaves)) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "the tree would have about %.3g stems and %.3g leaves (limits %.3g and %.3g); "
                  "use --force to grow it anyway",
                  estimate.stems, estimate.leaves, options.max_stems, options.max_leaves);
    throw RuntimeFailure(buf);
  }
  Skeleton skeleton;
  skeleton.stems.reserve(static_cast<size_t>(std::min(estimate.stems, 1e6)));
  skeleton.leaves.reserve(static_cast<size_t>(std::min(estimate.leaves, 4e6)));
  if (options.progress) options.progress->set_total(static_cast<std::uint64_t>(estimate.stems));
  Grower grower(params, options, skeleton);
  grower.grow();
  int max_level = 0;
  for (const Stem& s : skeleton.stems) max_level = std::max(max_level, s.level);
  skeleton.levels = max_level + 1;
  return skeleton;
}

}  // namespace arbor::generator
