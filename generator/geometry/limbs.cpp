// Limb chains, dominance at branch points, spline fitting and frame propagation.
#include "generator/geometry/limbs.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "common/error.h"

namespace arbor::generator {

namespace {

DVec3 point_of(const Skeleton& sk, std::int32_t stem, std::uint32_t i) {
  const Stem& s = sk.stems[static_cast<size_t>(stem)];
  return DVec3(sk.points[s.first_point + i].position);
}

double z_of(const Stem& s, std::uint32_t i) {
  if (s.point_count < 2) return s.z_start;
  return s.z_start + (1.0 - s.z_start) * i / (s.point_count - 1);
}

// Knot of `parent` nearest to a stem starting at `offset` metres along it.
std::uint32_t nearest_knot(const Stem& parent, double offset) {
  const double z = parent.length > 0.0f ? offset / parent.length : 0.0;
  const double f = (z - parent.z_start) / std::max(1e-9, 1.0 - parent.z_start);
  const double k = std::round(f * (parent.point_count - 1));
  return static_cast<std::uint32_t>(std::clamp(k, 0.0, parent.point_count - 1.0));
}

std::uint64_t knot_key(std::int32_t stem, std::uint32_t point) {
  return (static_cast<std::uint64_t>(stem) << 32) | point;
}

// Where a limb starts: a stem's point, and where it branches from.
struct Start {
  KnotRef knot;
  bool from_knot = false;  // branches at a knot of its parent (a branch point)
  KnotRef origin;          // that knot, when from_knot
  std::int32_t parent_stem = -1;
  double parent_offset = 0.0;  // for mid-segment children
};

struct Topology {
  std::vector<Start> starts;
  std::map<std::uint64_t, std::int32_t> takeover;  // (stem, knot) → clone that continues there
};

// Dominance at every branch point (Bloomenthal §5): the outgoing limb of largest radius, or if
// radii are nearly equal, the one that diverges least from the incoming direction.
Topology branch_topology(const Skeleton& sk) {
  Topology topo;
  std::map<std::uint64_t, std::vector<std::int32_t>> at_knot;
  for (size_t i = 0; i < sk.stems.size(); ++i) {
    const Stem& c = sk.stems[i];
    if (c.parent < 0) {
      topo.starts.push_back({{static_cast<std::int32_t>(i), 0}, false, {}, -1, 0.0});
      continue;
    }
    const Stem& p = sk.stems[static_cast<size_t>(c.parent)];
    const std::uint32_t k = c.parent_point >= 0 ? static_cast<std::uint32_t>(c.parent_point)
                                                : nearest_knot(p, c.parent_offset);
    const double gap =
        glm::length(point_of(sk, static_cast<std::int32_t>(i), 0) - point_of(sk, c.parent, k));
    if (k >= 1 && gap <= 1e-5 * std::max(1.0f, p.length)) {
      at_knot[knot_key(c.parent, k)].push_back(static_cast<std::int32_t>(i));
    } else {
      topo.starts.push_back(
          {{static_cast<std::int32_t>(i), 0}, false, {}, c.parent, c.parent_offset});
    }
  }
  for (const auto& [key, children] : at_knot) {
    const auto p = static_cast<std::int32_t>(key >> 32);
    const auto k = static_cast<std::uint32_t>(key & 0xffffffffu);
    const Stem& parent = sk.stems[static_cast<size_t>(p)];
    const DVec3 here = point_of(sk, p, k);
    const DVec3 incoming = glm::normalize(here - point_of(sk, p, k - 1));
    struct Option {
      std::int32_t stem;
      bool continuation;
      double radius;
      double divergence;
    };
    std::vector<Option> options;
    if (k + 1 < parent.point_count) {
      const DVec3 d = glm::normalize(point_of(sk, p, k + 1) - here);
      options.push_back({p, true, sk.points[parent.first_point + k].radius,
                         std::acos(std::clamp(glm::dot(d, incoming), -1.0, 1.0))});
    }
    for (std::int32_t c : children) {
      const Stem& cs = sk.stems[static_cast<size_t>(c)];
      const DVec3 d = glm::normalize(point_of(sk, c, 1) - here);
      options.push_back({c, false, sk.points[cs.first_point].radius,
                         std::acos(std::clamp(glm::dot(d, incoming), -1.0, 1.0))});
    }
    double largest = 0.0;
    for (const Option& o : options) largest = std::max(largest, o.radius);
    const Option* dominant = nullptr;
    for (const Option& o : options) {
      if (o.radius < largest * (1.0 - kNearlyEqualRadius)) continue;
      if (!dominant || o.divergence < dominant->divergence) dominant = &o;
    }
    for (const Option& o : options) {
      if (&o == dominant) {
        if (!o.continuation) topo.takeover[key] = o.stem;
        continue;
      }
      // A non-dominant continuation of the parent restarts at the branch point itself.
      const KnotRef first = o.continuation ? KnotRef{p, k} : KnotRef{o.stem, 0};
      topo.starts.push_back({first, true, {p, k}, p, 0.0});
    }
  }
  std::sort(topo.starts.begin(), topo.starts.end(), [](const Start& a, const Start& b) {
    return a.knot.stem != b.knot.stem ? a.knot.stem < b.knot.stem : a.knot.point < b.knot.point;
  });
  return topo;
}

// Follows a chain from its start through continuations and dominant clones.
std::vector<KnotRef> walk_chain(const Skeleton& sk, const Topology& topo, KnotRef at) {
  std::vector<KnotRef> knots{at};
  for (;;) {
    const Stem& s = sk.stems[static_cast<size_t>(at.stem)];
    const auto over = topo.takeover.find(knot_key(at.stem, at.point));
    if (over != topo.takeover.end() && knots.size() > 1) {
      at = {over->second, 1};  // the clone's point 0 duplicates this knot
    } else if (at.point + 1 < s.point_count) {
      at = {at.stem, at.point + 1};
    } else {
      break;
    }
    knots.push_back(at);
  }
  return knots;
}

// Arc length of a spline segment by 5-point Gauss–Legendre quadrature of |P'|.
double segment_arc(const CubicSpline& s, std::size_t i) {
  static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                              0.9061798459386640};
  static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                              0.2369268850561891, 0.2369268850561891};
  const double a = s.params[i], b = s.params[i + 1];
  double sum = 0.0;
  for (int k = 0; k < 5; ++k) {
    sum += w[k] * glm::length(s.derivative(0.5 * (a + b) + 0.5 * (b - a) * x[k]));
  }
  return 0.5 * (b - a) * sum;
}

}  // namespace

double branch_tension(double child_radius, double parent_radius) {
  if (parent_radius <= 0.0) return 1.0;
  return std::clamp(child_radius / parent_radius, kMinTension, 1.0);
}

double start_bend_ratio(const Skeleton& sk, const Limb& limb) {
  const double a = limb.spline.params[0], b = limb.spline.params[1];
  double worst = 0.0;
  for (int k = 0; k <= 16; ++k) {
    const double t = a + (b - a) * k / 16.0;
    worst = std::max(worst, limb.radius_at(sk, t) * limb.spline.curvature(t));
  }
  return worst;
}

double Limb::z_at(const Skeleton& sk, double t) const {
  double u = 0.0;
  const std::size_t i = spline.locate(t, u);
  return z_in(sk, i, u);
}

double Limb::z_in(const Skeleton& sk, std::size_t i, double u) const {
  const Stem& s = sk.stems[static_cast<size_t>(segment_stem(i))];
  // The segment's start knot may belong to the parent (where a clone takes over): there the
  // clone's own z starts.
  const double z0 = knots[i].stem == segment_stem(i) ? z_of(s, knots[i].point) : s.z_start;
  const double z1 = z_of(s, knots[i + 1].point);
  return z0 + (z1 - z0) * u;
}

double Limb::radius_at(const Skeleton& sk, double t) const {
  double u = 0.0;
  const std::size_t i = spline.locate(t, u);
  return radius_in(sk, i, u);
}

double Limb::radius_in(const Skeleton& sk, std::size_t i, double u) const {
  return sk.radius_at(sk.stems[static_cast<size_t>(segment_stem(i))], z_in(sk, i, u));
}

double Limb::arc_at(double t) const {
  double u = 0.0;
  const std::size_t i = spline.locate(t, u);
  return knot_arc[i] + (knot_arc[i + 1] - knot_arc[i]) * u;
}

DVec3 Limb::normal_at(double t) const {
  double u = 0.0;
  const std::size_t i = spline.locate(t, u);
  const std::vector<FrameSample> f =
      rotation_minimizing_frames(spline, {spline.params[i], t}, knot_normals[i]);
  return f.back().normal;
}

std::vector<Limb> fit_limbs(const Skeleton& sk) {
  const Topology topo = branch_topology(sk);
  std::vector<Limb> limbs;
  limbs.reserve(topo.starts.size());
  // Which limb passes through each knot (not counting knots where a limb merely starts).
  std::map<std::uint64_t, std::pair<std::int32_t, std::size_t>> through;

  for (const Start& start : topo.starts) {
    Limb limb;
    limb.knots = walk_chain(sk, topo, start.knot);
    if (limb.knots.size() < 2) continue;
    limb.level = sk.stems[static_cast<size_t>(start.knot.stem)].level;
    std::vector<DVec3> points;
    points.reserve(limb.knots.size());
    for (const KnotRef& k : limb.knots) points.push_back(point_of(sk, k.stem, k.point));
    const DVec3 first_chord = glm::normalize(points[1] - points[0]);
    const DVec3 last_chord = glm::normalize(points.back() - points[points.size() - 2]);

    DVec3 start_derivative = first_chord;
    DVec3 initial_normal = any_perpendicular(first_chord);
    double start_arc = 0.0;
    const std::pair<std::int32_t, std::size_t>* origin = nullptr;
    double origin_param = 0.0;
    if (start.from_knot) {
      const auto it = through.find(knot_key(start.origin.stem, start.origin.point));
      if (it != through.end()) {
        origin = &it->second;
        origin_param = limbs[static_cast<size_t>(origin->first)].spline.params[origin->second];
      }
    } else if (start.parent_stem >= 0) {
      // A child in the middle of a parent segment: find the limb holding that segment.
      const Stem& p = sk.stems[static_cast<size_t>(start.parent_stem)];
      const double z = p.length > 0.0f ? start.parent_offset / p.length : 0.0;
      const double f = std::clamp((z - p.z_start) / std::max(1e-9, 1.0 - p.z_start), 0.0, 1.0) *
                       (p.point_count - 1);
      const auto j = static_cast<std::uint32_t>(std::min(std::floor(f), p.point_count - 2.0));
      const auto it = through.find(knot_key(start.parent_stem, j + 1));
      if (it != through.end() && it->second.second >= 1) {
        origin = &it->second;
        const CubicSpline& ps = limbs[static_cast<size_t>(origin->first)].spline;
        const double frac = f - j;
        origin_param = ps.params[origin->second - 1] +
                       frac * (ps.params[origin->second] - ps.params[origin->second - 1]);
      }
    }
    if (origin) {
      const Limb& parent = limbs[static_cast<size_t>(origin->first)];
      limb.parent = origin->first;
      limb.parent_param = origin_param;
      const double parent_radius = parent.radius_at(sk, origin_param);
      const KnotRef base = limb.knots[0];
      const Stem& own = sk.stems[static_cast<size_t>(base.stem)];
      const double own_radius = sk.points[own.first_point + base.point].radius;
      limb.tension = branch_tension(own_radius, parent_radius);
      DVec3 parent_direction = parent.spline.derivative(origin_param);
      parent_direction =
          glm::length(parent_direction) > 1e-12 ? glm::normalize(parent_direction) : first_chord;
      start_derivative = limb.tension * parent_direction;  // Bloomenthal Fig. 5
      initial_normal = parent.normal_at(origin_param);
      start_arc = parent.arc_at(origin_param);
      // The skeleton puts the child on the chord between its parent's points; the parent's limb
      // is the spline through them, up to a few centimetres off a long chord: the child starts on
      // the spline, the axis the renderer draws.
      points[0] = parent.spline.position(origin_param);
    }
    limb.spline = fit_c2_spline(points, start_derivative, last_chord);
    if (origin) {
      // A short clamped tangent makes the limb turn sharply at its base; Embree needs the radius
      // below the radius of curvature there, so raise the tension until the bend is wide enough.
      while (limb.tension < 1.0 && start_bend_ratio(sk, limb) >= 0.95) {
        limb.tension = std::min(1.0, limb.tension * 1.5);
        limb.tension_raised = true;
        start_derivative = limb.tension * glm::normalize(start_derivative);
        limb.spline = fit_c2_spline(points, start_derivative, last_chord);
      }
    }
    const std::vector<FrameSample> frames =
        rotation_minimizing_frames(limb.spline, limb.spline.params, initial_normal);
    limb.knot_normals.reserve(frames.size());
    for (const FrameSample& f : frames) limb.knot_normals.push_back(f.normal);
    limb.knot_arc.assign(limb.knots.size(), start_arc);
    for (std::size_t i = 0; i + 1 < limb.knots.size(); ++i) {
      limb.knot_arc[i + 1] = limb.knot_arc[i] + segment_arc(limb.spline, i);
    }
    const auto index = static_cast<std::int32_t>(limbs.size());
    for (std::size_t i = 1; i < limb.knots.size(); ++i) {
      through[knot_key(limb.knots[i].stem, limb.knots[i].point)] = {index, i};
    }
    if (limb.parent < 0 && limb.knots.front().point == 0) {
      through[knot_key(limb.knots[0].stem, 0)] = {index, 0};
    }
    limbs.push_back(std::move(limb));
  }
  return limbs;
}

}  // namespace arbor::generator
