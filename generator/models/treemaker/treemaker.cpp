// TREE-MAKER particle growth. arbor's readings of the paper are stated where they are made and in
// docs/treemaker-format.md.
#include "generator/models/treemaker/treemaker.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "common/frame.h"
#include "common/rng.h"
#include "generator/grow_options.h"

namespace arbor::generator {

namespace {

double uniform(Rng& rng, const TmRange& r) { return r.lo + (r.hi - r.lo) * rng.uniform(); }

// The weakest channel of a primitive's colour, at least this share of its strongest: measured
// leaves are never purer (blue about 0.3 of green; docs/species-format.md, "Leaf colours").
constexpr double kMinChannelShare = 0.3;

// A colour's weights normalised to its largest (only ratios matter, §V), times a brightness: a
// display value of the 1990 frame buffer, so decoded as sRGB to a linear one, whose weaker
// channels are then raised to kMinChannelShare of its strongest (docs/treemaker-format.md,
// "Colours"): the paper's pure green (0, 1, 0) at brightness 0.6 becomes (0.096, 0.319, 0.096).
glm::vec3 shade(const TreeMakerTemplate& t, const std::string& name, double brightness) {
  const TmColor* c = t.color(name);
  glm::dvec3 rgb(1.0);
  if (c) rgb = c->rgb / std::max({c->rgb.x, c->rgb.y, c->rgb.z});
  glm::dvec3 linear;
  for (int i = 0; i < 3; ++i) {
    const double v = rgb[i] * brightness;
    linear[i] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  const double top = std::max({linear.x, linear.y, linear.z});
  return glm::vec3(glm::max(linear, glm::dvec3(kMinChannelShare * top)));
}

// A unit vector at `angle` degrees from `axis`, turned `dir` degrees about it from the horizontal
// (0 and 180: horizontal on either side; 90: up), as the branching rules use them (Figure 1).
Vec3 branch_direction(const Vec3& axis, double angle, double dir) {
  Vec3 up = Vec3(0, 0, 1) - axis * axis.z;
  if (glm::length(up) < 1e-6) up = Vec3(0, 1, 0) - axis * axis.y;  // a vertical parent
  up = glm::normalize(up);
  const Vec3 side = glm::cross(up, axis);
  const Vec3 around = side * std::cos(radians(dir)) + up * std::sin(radians(dir));
  return glm::normalize(axis * std::cos(radians(angle)) + around * std::sin(radians(angle)));
}

class Grower {
 public:
  Grower(const TreeMakerTemplate& t, const TreeMakerOptions& o) : t_(t), o_(o) {}

  Skeleton run() {
    for (std::size_t i = 0; i < t_.particles.size(); ++i) {
      const TmParticle& def = t_.particles[i];
      Particle p;
      p.key = derive_key(o_.seed, 100 + i);
      Rng rng(p.key);
      p.pos = def.pos * kTreeMakerUnit;
      // The starting direction lies within max_deviation of the template's dir.
      const Vec3 base = glm::normalize(def.dir);
      const double tilt = radians(def.max_deviation) * std::sqrt(rng.uniform());
      p.dir = glm::normalize(rotate(base, any_perpendicular(base), tilt));
      p.dir = glm::normalize(rotate(p.dir, base, 2.0 * kPi * rng.uniform()));
      p.mag = def.mag;
      p.acc = def.acc;
      p.growth = def.growth;
      p.age = def.age;
      p.def = static_cast<int>(i);
      p.color = shade(t_, def.color, uniform(rng, def.brightness));
      if (i == 0) {
        add_stem(p, -1, -1);
      } else if (glm::length(def.pos - t_.particles[0].pos) < 1e-9) {
        // Several particles from one point: stems of a shrub from the root point.
        add_stem(p, 0, 0);
      } else {
        throw InputError(def.where,
                         "every particle must start at the first particle's pos: a tree "
                         "has one root (Bloomenthal's skeleton)");
      }
      particles_.push_back(p);
    }
    for (int it = 0; it < t_.iterations; ++it) iterate();
    finish();
    return std::move(sk_);
  }

 private:
  struct Particle {
    std::uint64_t key = 0;
    int stem = -1, level = 0, def = 0, children = 0;
    Vec3 pos{0.0}, dir{0, 0, 1};
    TmRange mag;
    double acc = 0.0, growth = 0.0, age = 0.0;
    glm::vec3 color{1.0f};
  };
  struct Branch {
    std::vector<Vec3> positions;
    std::vector<double> widths;  // template units
    int parent = -1, parent_point = -1, level = 0;
    Vec3 parent_position{0.0};  // where on the parent it starts
    glm::vec3 color{1.0f};
  };

  // Index of the (merged) parent point at `at`.
  static int point_of(const Branch& b, const Vec3& at) {
    for (std::size_t k = 0; k < b.positions.size(); ++k) {
      if (glm::length(b.positions[k] - at) < 1e-9) return static_cast<int>(k);
    }
    return 0;
  }

  // The stem a particle's leaf goes on: its own, or the nearest ancestor's that was kept.
  int kept_stem(int branch) const {
    while (branch >= 0 && stem_index_[static_cast<size_t>(branch)] < 0)
      branch = branches_[static_cast<size_t>(branch)].parent;
    return branch >= 0 ? stem_index_[static_cast<size_t>(branch)] : 0;
  }

  static Vec3 any_perpendicular(const Vec3& v) {
    const Vec3 a = std::fabs(v.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    return glm::normalize(glm::cross(a, v));
  }

  void add_stem(Particle& p, int parent, int parent_point) {
    Branch b;
    b.parent = parent;
    b.parent_point = parent_point;
    if (parent >= 0) {
      const std::vector<Vec3>& ps = branches_[static_cast<size_t>(parent)].positions;
      b.parent_position = ps.empty() ? p.pos : ps[static_cast<size_t>(parent_point)];
    }
    b.level = p.level;
    b.color = p.color;
    branches_.push_back(b);
    p.stem = static_cast<int>(branches_.size()) - 1;
    refuse_growth(o_.force, static_cast<double>(branches_.size()), o_.max_stems,
                  "the template grew past", "branches");
  }

  // One iteration (§II): every particle stores its position, widens its limb, branches by the
  // rules, moves by its growth vector, ages and bends under gravity.
  void iterate() {
    std::vector<Particle> born;
    for (Particle& p : particles_) {
      Branch& b = branches_[static_cast<size_t>(p.stem)];
      b.positions.push_back(p.pos);
      b.widths.push_back(0.0);
      for (double& w : b.widths) w += p.growth;
      // A negative age shrinks the width growth, never below zero (as acc does the magnitude).
      p.growth = std::max(0.0, p.growth + p.age);
      Rng rng(derive_key(p.key, b.positions.size()));
      if (const TmBranchRule* rule = t_.rule_for(p.level + 1)) {
        // The count is drawn from the uniform range and truncated (§V, dogwood level 2).
        const int count = static_cast<int>(uniform(rng, rule->number));
        for (int k = 0; k < count; ++k) born.push_back(branch(p, *rule, rng));
      }
      p.pos += p.dir * (uniform(rng, p.mag) * kTreeMakerUnit);
      // Aging: acc is added to both ends of the magnitude range (never below zero).
      p.mag.lo = std::max(0.0, p.mag.lo + p.acc);
      p.mag.hi = std::max(0.0, p.mag.hi + p.acc);
      // Gravity: g × cos(angle to the horizontal) off the z component of the growth vector (of
      // the range's mean magnitude, in template units), renormalised to keep its magnitude.
      const double magnitude = 0.5 * (p.mag.lo + p.mag.hi);
      if (magnitude > 1e-9) {
        const double cos_horizontal = std::sqrt(p.dir.x * p.dir.x + p.dir.y * p.dir.y);
        Vec3 v = p.dir * magnitude;
        v.z -= t_.gravity * cos_horizontal;
        if (glm::length(v) > 1e-12) p.dir = glm::normalize(v);
      }
    }
    particles_.insert(particles_.end(), born.begin(), born.end());
  }

  Particle branch(Particle& parent, const TmBranchRule& rule, Rng& rng) {
    double pick = rng.uniform();
    const TmBranchChoice* choice = &rule.choices.back();
    for (const TmBranchChoice& c : rule.choices) {
      if (pick < c.p) {
        choice = &c;
        break;
      }
      pick -= c.p;
    }
    const double angle = uniform(rng, choice->angle), dir = uniform(rng, choice->dir);
    const double factor = uniform(rng, choice->factor);
    Particle c;
    c.key = derive_key(parent.key, 1000 + static_cast<std::uint64_t>(parent.children++));
    c.level = parent.level + 1;
    c.def = parent.def;
    c.pos = parent.pos;
    c.dir = branch_direction(parent.dir, angle, dir);
    // The growth reduction factor scales the new limb's length and width (§V, level 1).
    c.mag = {parent.mag.lo * factor, parent.mag.hi * factor};
    c.acc = parent.acc * factor;
    c.growth = parent.growth * factor;
    c.age = parent.age * factor;
    Rng own(c.key);
    const TmParticle& def = t_.particles[static_cast<size_t>(c.def)];
    c.color = shade(t_, def.color, uniform(own, def.brightness));
    add_stem(c, parent.stem,
             static_cast<int>(branches_[static_cast<size_t>(parent.stem)].positions.size()) - 1);
    return c;
  }

  void finish() {
    // The last positions are stored; then a leaf goes on the end of every branch (§II).
    for (Particle& p : particles_) {
      Branch& b = branches_[static_cast<size_t>(p.stem)];
      b.positions.push_back(p.pos);
      b.widths.push_back(0.0);
    }
    // Stems: a branch that never moved (born in the last iteration, or aged to no growth) has no
    // length and is left out; its leaf goes on its parent.
    std::vector<int> index(branches_.size(), -1);
    for (std::size_t i = 0; i < branches_.size(); ++i) {
      Branch& b = branches_[i];
      // Consecutive positions that coincide (no growth) are one point, at the larger width.
      std::vector<Vec3> positions;
      std::vector<double> widths;
      for (std::size_t k = 0; k < b.positions.size(); ++k) {
        if (!positions.empty() && glm::length(b.positions[k] - positions.back()) < 1e-9) {
          widths.back() = std::max(widths.back(), b.widths[k]);
          continue;
        }
        positions.push_back(b.positions[k]);
        widths.push_back(b.widths[k]);
      }
      b.positions = positions;
      b.widths = widths;
      const bool moved = b.parent < 0 ? b.positions.size() >= 2 : b.positions.size() >= 2;
      if (!moved || (b.parent >= 0 && index[static_cast<size_t>(b.parent)] < 0)) continue;
      Stem st;
      st.parent = b.parent >= 0 ? index[static_cast<size_t>(b.parent)] : -1;
      st.parent_point = b.parent_point;
      st.level = b.level;
      st.taper = -1.0f;
      st.color = b.color;
      std::vector<SkeletonPoint> pts;
      if (b.parent >= 0) {
        // A branch starts at its parent's stored position: that point is its first one.
        const Branch& pb = branches_[static_cast<size_t>(b.parent)];
        st.parent_point = point_of(pb, b.parent_position);
        const double parent_width = pb.widths[static_cast<size_t>(st.parent_point)];
        const double own = b.widths.empty() ? 0.0 : b.widths.front();
        pts.push_back({glm::vec3(pb.positions[static_cast<size_t>(st.parent_point)]),
                       static_cast<float>(0.5 * std::min(parent_width, own) * kTreeMakerUnit)});
      }
      for (std::size_t k = 0; k < b.positions.size(); ++k) {
        pts.push_back(
            {glm::vec3(b.positions[k]), static_cast<float>(0.5 * b.widths[k] * kTreeMakerUnit)});
      }
      if (b.parent >= 0 && pts.size() >= 2 &&
          glm::length(pts[1].position - pts[0].position) < 1e-7f) {
        pts.erase(pts.begin() + 1);  // the branch's first stored position is the branch point
      }
      st.first_point = static_cast<std::uint32_t>(sk_.points.size());
      st.point_count = static_cast<std::uint32_t>(pts.size());
      float length = 0.0f;
      for (std::size_t k = 1; k < pts.size(); ++k)
        length += glm::length(pts[k].position - pts[k - 1].position);
      st.length = length;
      st.base_radius = pts.front().radius;
      // A child starting at its parent's first point starts at the point the parent itself grew
      // from: it belongs to the stem that owns that point (one owner per point, as in a
      // skeleton file).
      while (st.parent >= 0 && st.parent_point == 0 &&
             sk_.stems[static_cast<size_t>(st.parent)].parent >= 0) {
        const Stem& ps = sk_.stems[static_cast<size_t>(st.parent)];
        st.parent_point = ps.parent_point;
        st.parent = ps.parent;
      }
      if (b.parent >= 0) {
        const Stem& ps = sk_.stems[static_cast<size_t>(st.parent)];
        // Re-parented to the point its parent grew from, a limb starts no thicker than the new
        // parent is there (its old parent's own base width may be larger).
        pts.front().radius = std::min(
            pts.front().radius,
            sk_.points[ps.first_point + static_cast<std::uint32_t>(st.parent_point)].radius);
        st.base_radius = pts.front().radius;
        float arc = 0.0f;
        for (int k = 1; k <= st.parent_point; ++k) {
          arc += glm::length(sk_.points[ps.first_point + k].position -
                             sk_.points[ps.first_point + k - 1].position);
        }
        st.parent_offset = arc;
      }
      sk_.points.insert(sk_.points.end(), pts.begin(), pts.end());
      index[i] = static_cast<int>(sk_.stems.size());
      sk_.stems.push_back(st);
    }
    stem_index_ = index;
    for (const Particle& p : particles_) {
      add_leaf(p, leaf_index_);
      ++leaf_index_;
    }
    int levels = 1;
    for (const Stem& s : sk_.stems) levels = std::max(levels, s.level + 1);
    sk_.levels = levels;
  }

  // A leaf, chosen by probability, placed in leaf or limb coordinates within the out and up
  // deviations (§IV): z is the leaf's out axis, y its up axis.
  void add_leaf(const Particle& p, std::int32_t index) {
    Rng rng(derive_key(p.key, 0x1eaf));
    double pick = rng.uniform();
    const TmLeaf* leaf = &t_.leaves.back();
    for (const TmLeaf& l : t_.leaves) {
      if (pick < l.p) {
        leaf = &l;
        break;
      }
      pick -= l.p;
    }
    Vec3 out = p.dir, up(0, 0, 1);
    if (!leaf->limb_coords) {
      // Leaf coordinates: out is the branch's horizontal direction, up is the world's up.
      out = Vec3(p.dir.x, p.dir.y, 0.0);
      out = glm::length(out) > 1e-6 ? glm::normalize(out) : Vec3(1, 0, 0);
    } else {
      up = up - out * glm::dot(up, out);
      up = glm::length(up) > 1e-6 ? glm::normalize(up) : any_perpendicular(out);
    }
    // Out deviation: tilt out by up to `out` degrees in a random direction; up deviation: twist
    // about out by up to ±`up` degrees.
    const Vec3 tilt_axis =
        rotate(glm::normalize(glm::cross(out, up)), out, 2.0 * kPi * rng.uniform());
    const double tilt = radians(leaf->out) * rng.uniform();
    out = glm::normalize(rotate(out, tilt_axis, tilt));
    up = glm::normalize(rotate(up, tilt_axis, tilt));
    up = glm::normalize(rotate(up, out, radians(leaf->up) * rng.symmetric()));
    const Vec3 x = glm::cross(up, out);
    auto place = [&](const glm::dvec3& v) {
      return glm::vec3(p.pos + (x * v.x + up * v.y + out * v.z) * kTreeMakerUnit);
    };
    for (const TmElement& e : leaf->elements) {
      const glm::vec3 color = shade(t_, e.color, uniform(rng, e.brightness));
      if (e.line) {
        LeafLine l;
        l.a = place(e.v[0]);
        l.b = place(e.v[1]);
        l.color = color;
        l.stem = kept_stem(p.stem);
        l.leaf = index;
        sk_.leaf_lines.push_back(l);
      } else {
        LeafTriangle tri;
        for (int k = 0; k < 3; ++k) tri.v[k] = place(e.v[static_cast<size_t>(k)]);
        tri.color = color;
        tri.stem = kept_stem(p.stem);
        tri.leaf = index;
        sk_.leaf_triangles.push_back(tri);
      }
    }
  }

  const TreeMakerTemplate& t_;
  const TreeMakerOptions& o_;
  std::vector<Particle> particles_;
  std::vector<Branch> branches_;
  std::int32_t leaf_index_ = 0;
  std::vector<int> stem_index_;  // branch → stem, -1 for branches left out
  Skeleton sk_;
};

}  // namespace

double treemaker_estimate(const TreeMakerTemplate& t) {
  // The most branches one particle can grow: f(l, n), for a branch of level l with n iterations
  // left, is itself plus, each later iteration, as many level-(l+1) branches as its rule allows
  // at most, each growing for the iterations left after it: f(l, n) = 1 + p(l+1) Σ_{r<n} f(l+1, r).
  // Levels stop at 1000 (the template's largest). Tabulated by n with running sums over r:
  // O(iterations × levels), about a million steps at the limits, not the recursion's billion.
  constexpr int kLevels = 1000;
  std::vector<double> per_iteration(kLevels + 2, 0.0);
  for (int l = 0; l <= kLevels + 1; ++l) {
    const TmBranchRule* rule = t.rule_for(l);
    per_iteration[static_cast<size_t>(l)] = rule ? std::floor(rule->number.hi) : 0.0;
  }
  const int n_max = t.iterations + 1;
  std::vector<double> sum(kLevels + 1, 0.0);  // Σ_{r ≤ n-1} f(l, r), for every level l
  std::vector<double> f(kLevels + 1, 0.0);
  for (int n = 1; n <= n_max; ++n) {
    for (int l = 0; l <= kLevels; ++l) {
      const double p = per_iteration[static_cast<size_t>(l + 1)];
      f[static_cast<size_t>(l)] =
          1.0 + (p > 0.0 ? p * sum[static_cast<size_t>(std::min(l + 1, kLevels))] : 0.0);
    }
    for (int l = 0; l <= kLevels; ++l) sum[static_cast<size_t>(l)] += f[static_cast<size_t>(l)];
  }
  return f[0] * static_cast<double>(t.particles.size());
}

Skeleton grow_treemaker(const TreeMakerTemplate& t, const TreeMakerOptions& o) {
  const double estimate = treemaker_estimate(t);
  refuse_estimate(o.force, estimate, o.max_stems, "the template could grow", "branches");
  return Grower(t, o).run();
}

}  // namespace arbor::generator
