// L-system language (Borenszweig 2008) with arbor's directives, and its 3D turtle.
#include "generator/models/lsystem/lsystem.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include <glm/geometric.hpp>

#include "common/frame.h"
#include "common/rng.h"
#include "common/text_cursor.h"
#include "generator/grow_options.h"

namespace arbor::generator {

namespace {

// The most one interpretation of `body` at recursion depth `depth` costs: its actions of any kind
// (`work`: what bounds the time, even for a system that draws nothing, A: A A;) or its f
// segments. `deeper` holds each rule's cost one depth further down.
double body_cost(const LSystem& sys, const std::vector<LAction>& body, int depth,
                 const std::array<double, 26>& deeper, bool work) {
  double n = 0.0;
  for (const LAction& a : body) {
    if (work || a.kind == LAction::Forward) n += 1.0;
    if (a.kind == LAction::Branch)
      n += body_cost(sys, a.branch, depth, deeper, work);
    else if (a.kind == LAction::Rule && depth + 1 <= sys.iterations)
      n += deeper[static_cast<size_t>(a.rule - 'A')];
  }
  return n;
}

// The axiom's cost, the most any choice of alternatives can reach: a table of every rule's cost
// filled from the deepest iteration up, so that no recursion runs through the rules (only
// through one body's brackets, at most 100 deep).
double axiom_cost(const LSystem& sys, bool work) {
  std::array<double, 26> deeper{};
  for (int depth = sys.iterations; depth >= 0; --depth) {
    std::array<double, 26> here{};
    for (const LRule& r : sys.rules) {
      double& worst = here[static_cast<size_t>(r.name - 'A')];
      worst = std::max(worst, body_cost(sys, r.body, depth, deeper, work));
    }
    deeper = here;
  }
  return deeper[static_cast<size_t>(sys.rules.front().name - 'A')];
}

// The turtle: position, orientation (heading, left, up), and the multipliers of the language.
struct Turtle {
  Vec3 position{0.0};
  Vec3 heading{0, 0, 1}, left{1, 0, 0}, up{0, 1, 0};
  double step = 1.0, radius = 0.05;
  double yaw = 1.0, pitch = 1.0, roll = 1.0;  // u, l, h multipliers
  int stem = -1;                              // stem being drawn; -1 before its first f
  int parent_stem = -1;                       // stem this branch grows from
  int parent_point = -1;                      // that stem's point where it starts
};

class Interpreter {
 public:
  Interpreter(const LSystem& sys, const LSystemOptions& o)
      : sys_(sys), o_(o), jitter_(derive_key(o.seed, 1)), choice_(derive_key(o.seed, 2)) {}

  Skeleton run() {
    Turtle t;
    t.step = sys_.step;
    t.radius = sys_.radius;
    interpret(choose(sys_.rules.front().name), t);
    finish_stems();
    add_leaves();
    int levels = 1;
    for (const Stem& s : sk_.stems) levels = std::max(levels, s.level + 1);
    sk_.levels = levels;
    return std::move(sk_);
  }

 private:
  double vary() {
    return sys_.randomness > 0.0 ? 1.0 + sys_.randomness * jitter_.symmetric() : 1.0;
  }

  // The body a rule of this name runs, chosen by weight (the number after a rule's name).
  const std::vector<LAction>& choose(char name) {
    double total = 0.0;
    for (const LRule& r : sys_.rules) total += r.name == name ? r.weight : 0.0;
    double pick = choice_.uniform() * total;
    for (const LRule& r : sys_.rules) {
      if (r.name != name) continue;
      pick -= r.weight;
      if (pick <= 0.0) return r.body;
    }
    for (auto it = sys_.rules.rbegin(); it != sys_.rules.rend(); ++it) {
      if (it->name == name) return it->body;
    }
    return sys_.rules.front().body;
  }

  void turn(Vec3& a, Vec3& b, double degrees) {
    const double r = radians(degrees), c = std::cos(r), s = std::sin(r);
    const Vec3 na = a * c + b * s, nb = b * c - a * s;
    a = na;
    b = nb;
  }

  void forward(const LAction& a, Turtle& t) {
    refuse_growth(o_.force, static_cast<double>(++segments_), o_.max_stems,
                  "the L-system drew more than", "segments");
    if (t.stem < 0) {
      if (t.parent_stem < 0 && !stems_.empty()) {
        throw InputError(a.where,
                         "a second trunk starts here: a tree has one root, so every "
                         "stem but the first must grow from another one");
      }
      start_stem(t);
    }
    const double length = t.step * (a.has_number ? a.number : 1.0) * vary();
    t.position += t.heading * length;
    // A limb segment needs a length and a place: one of length 0 has no direction (its spline
    // and frame would be NaN), and steps that s(n) multiplies without bound leave any scale.
    if (!(std::fabs(t.position.x) <= kMaxReach && std::fabs(t.position.y) <= kMaxReach &&
          std::fabs(t.position.z) <= kMaxReach)) {
      throw InputError(a.where,
                       "the turtle moves more than 1000 km from the root here (s(n) "
                       "multiplies the step at every use)");
    }
    std::vector<SkeletonPoint>& points = stems_[static_cast<size_t>(t.stem)].points;
    const glm::vec3 at(t.position);
    if (!(length >= kMinSegment) ||
        glm::length(at - points.back().position) < static_cast<float>(kMinSegment)) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "this move is %.3g m long; limb segments must be at least 1 micrometre "
                    "(the step has shrunk, or f(0))",
                    length);
      throw InputError(a.where, buf);
    }
    points.push_back({at, static_cast<float>(t.radius)});
  }

  void start_stem(Turtle& t) {
    OpenStem s;
    s.stem.parent = t.parent_stem;
    s.stem.parent_point = t.parent_point;
    s.stem.level =
        t.parent_stem < 0 ? 0 : stems_[static_cast<size_t>(t.parent_stem)].stem.level + 1;
    s.stem.taper = -1.0f;
    s.points.push_back({glm::vec3(t.position), static_cast<float>(t.radius)});
    if (t.parent_stem >= 0) {
      // Where along the parent: the arc length to the branch point.
      const OpenStem& p = stems_[static_cast<size_t>(t.parent_stem)];
      float arc = 0.0f;
      for (int i = 1; i <= t.parent_point; ++i)
        arc += glm::length(p.points[static_cast<size_t>(i)].position -
                           p.points[static_cast<size_t>(i - 1)].position);
      s.stem.parent_offset = arc;
      stems_[static_cast<size_t>(t.parent_stem)].has_children = true;
    }
    stems_.push_back(std::move(s));
    t.stem = static_cast<int>(stems_.size()) - 1;
  }

  // Interprets a rule's body with an explicit stack instead of recursion (64 iterations of
  // rules with brackets 100 deep would need thousands of frames): the same actions in the same
  // order as the recursive reading. A frame runs a body at a depth with a turtle; a rule
  // shares its caller's turtle, a branch has a copy of its own.
  void interpret(const std::vector<LAction>& axiom, Turtle start) {
    struct Frame {
      const std::vector<LAction>* body;
      std::size_t next;
      int depth;
      std::size_t turtle;
      bool own_turtle;
    };
    std::vector<Turtle> turtles{start};
    std::vector<Frame> frames{{&axiom, 0, 0, 0, false}};
    while (!frames.empty()) {
      Frame& f = frames.back();
      if (f.next == f.body->size()) {
        if (f.own_turtle) turtles.pop_back();
        frames.pop_back();
        continue;
      }
      const LAction& a = (*f.body)[f.next++];
      const int depth = f.depth;
      const std::size_t turtle = f.turtle;
      Turtle& t = turtles[turtle];
      const double amount = a.has_number ? a.number : sys_.angle;
      switch (a.kind) {
        case LAction::Forward: forward(a, t); break;
        case LAction::TurnLeft: turn(t.heading, t.left, amount * t.yaw * vary()); break;
        case LAction::TurnRight: turn(t.heading, t.left, -amount * t.yaw * vary()); break;
        case LAction::PitchUp: turn(t.heading, t.up, amount * t.pitch * vary()); break;
        case LAction::PitchDown: turn(t.heading, t.up, -amount * t.pitch * vary()); break;
        case LAction::RollLeft: turn(t.left, t.up, amount * t.roll * vary()); break;
        case LAction::RollRight: turn(t.left, t.up, -amount * t.roll * vary()); break;
        case LAction::ScaleStep: t.step *= a.number; break;
        case LAction::ScaleRoll: t.roll *= a.number; break;
        case LAction::ScaleYaw: t.yaw *= a.number; break;
        case LAction::ScalePitch: t.pitch *= a.number; break;
        case LAction::ScaleRadius: t.radius *= a.number; break;
        case LAction::Rule:
          // Iterations bound the recursion: a rule is consumed only down to that depth.
          if (depth + 1 <= sys_.iterations)
            frames.push_back({&choose(a.rule), 0, depth + 1, turtle, false});
          break;
        case LAction::Branch: {
          Turtle inner = t;
          if (t.stem >= 0) {
            inner.parent_stem = t.stem;
            inner.parent_point =
                static_cast<int>(stems_[static_cast<size_t>(t.stem)].points.size()) - 1;
          }
          inner.stem = -1;
          turtles.push_back(inner);
          frames.push_back({&a.branch, 0, depth, turtles.size() - 1, true});
          break;
        }
      }
    }
  }

  void finish_stems() {
    for (OpenStem& s : stems_) {
      ARBOR_CHECK(s.points.size() >= 2);  // a stem starts at its first f: base and one point
      Stem st = s.stem;
      st.first_point = static_cast<std::uint32_t>(sk_.points.size());
      st.point_count = static_cast<std::uint32_t>(s.points.size());
      float length = 0.0f;
      for (std::size_t i = 1; i < s.points.size(); ++i)
        length += glm::length(s.points[i].position - s.points[i - 1].position);
      st.length = length;
      st.base_radius = s.points.front().radius;
      sk_.points.insert(sk_.points.end(), s.points.begin(), s.points.end());
      sk_.stems.push_back(st);
      tips_.push_back(!s.has_children);
    }
  }

  // Leaves at the tip of every stem without branches, set evenly round it, 45° out.
  void add_leaves() {
    if (sys_.leaves <= 0) return;
    for (std::size_t i = 0; i < sk_.stems.size(); ++i) {
      if (!tips_[i]) continue;
      const Stem& s = sk_.stems[i];
      const glm::dvec3 tip(sk_.points[s.first_point + s.point_count - 1].position);
      const glm::dvec3 prev(sk_.points[s.first_point + s.point_count - 2].position);
      const glm::dvec3 h = glm::normalize(tip - prev);
      const glm::dvec3 side = glm::normalize(
          glm::cross(h, std::fabs(h.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
      for (int k = 0; k < sys_.leaves; ++k) {
        const glm::dvec3 out = rotate(side, h, 2.0 * kPi * k / sys_.leaves);
        const glm::dvec3 axis = glm::normalize(h + out);
        Leaf leaf;
        leaf.position = glm::vec3(tip);
        leaf.axis = glm::vec3(axis);
        leaf.normal = glm::vec3(glm::normalize(glm::cross(axis, glm::cross(out, h))));
        leaf.length = static_cast<float>(sys_.leaf_length);
        leaf.width = static_cast<float>(sys_.leaf_width);
        leaf.stem = static_cast<std::int32_t>(i);
        leaf.shape = sys_.leaf_shape;
        sk_.leaves.push_back(leaf);
      }
    }
  }

  struct OpenStem {
    Stem stem;
    std::vector<SkeletonPoint> points;
    bool has_children = false;
  };

  static constexpr double kMaxReach = 1e6;     // metres from the root
  static constexpr double kMinSegment = 1e-6;  // metres
  const LSystem& sys_;
  const LSystemOptions& o_;
  Rng jitter_, choice_;
  std::vector<OpenStem> stems_;
  std::vector<bool> tips_;
  double segments_ = 0.0;
  Skeleton sk_;
};

}  // namespace

double estimate_segments(const LSystem& sys) { return axiom_cost(sys, false); }

Skeleton grow_lsystem(const LSystem& sys, const LSystemOptions& o) {
  const double estimate = estimate_segments(sys);
  refuse_estimate(o.force, estimate, o.max_stems, "the L-system would draw", "segments");
  refuse_estimate(o.force, axiom_cost(sys, true), 50.0 * o.max_stems,
                  "the L-system would interpret", "actions");
  return Interpreter(sys, o).run();
}

}  // namespace arbor::generator
