// Statistics of a Skeleton.
#include "generator/export/tree_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/json.h"
#include "generator/geometry/leaf_shapes.h"

namespace arbor::generator {

long long TreeStats::stems() const {
  long long total = 0;
  for (long long n : stems_per_level) total += n;
  return total;
}

TreeStats compute_stats(const Skeleton& sk) {
  TreeStats st;
  st.stems_per_level.assign(static_cast<size_t>(std::max(1, sk.levels)), 0);
  for (const Stem& s : sk.stems) {
    if (static_cast<size_t>(s.level) >= st.stems_per_level.size()) {
      st.stems_per_level.resize(static_cast<size_t>(s.level) + 1, 0);
    }
    ++st.stems_per_level[static_cast<size_t>(s.level)];
    st.skeleton_segments += s.point_count > 0 ? s.point_count - 1 : 0;
  }
  st.points = static_cast<long long>(sk.points.size());
  st.leaves = static_cast<long long>(sk.leaf_count());
  // The trunk's base (stems append their points after their children's, so not points[0]).
  const glm::vec3 axis =
      sk.stems.empty() ? glm::vec3(0.0f) : sk.points[sk.stems.front().first_point].position;
  double reach = 0.0, top = 0.0;
  auto visit = [&](const glm::vec3& p, double margin) {
    top = std::max(top, static_cast<double>(p.z) + margin);
    reach = std::max(reach, std::hypot(p.x - axis.x, p.y - axis.y) + margin);
  };
  for (const SkeletonPoint& p : sk.points) visit(p.position, p.radius);
  const auto& shapes = leaf_shapes();
  for (const Leaf& l : sk.leaves) {
    st.leaf_triangles +=
        static_cast<long long>(shapes[static_cast<size_t>(l.shape)].triangles.size());
    visit(l.position + l.axis * l.length, 0.5 * l.width);
  }
  st.leaf_triangles += static_cast<long long>(sk.leaf_triangles.size());
  for (const LeafTriangle& t : sk.leaf_triangles) {
    for (const glm::vec3& v : t.v) visit(v, 0.0);
  }
  st.triangles = st.leaf_triangles;
  st.curve_segments = st.skeleton_segments;
  st.height = top;
  st.crown_width = 2.0 * reach;
  return st;
}

void add_geometry_stats(TreeStats& st, const GeometryStats& g, double seconds) {
  st.has_geometry = true;
  st.geometry = g;
  st.geometry_seconds = seconds;
  st.curve_segments = static_cast<long long>(g.curve_segments);
  // Leaves: their drawn outlines' triangles (a margin's teeth included; the renderer holds them
  // as cards, g.leaf_cards) and the free-form triangles.
  st.leaf_triangles =
      static_cast<long long>(g.leaf_outline_triangles) + static_cast<long long>(g.leaf_triangles);
  st.triangles = st.leaf_triangles + static_cast<long long>(g.grid_triangles) +
                 static_cast<long long>(g.ramiform_triangles);
}

std::string stats_json(const TreeStats& st, const std::string& species, unsigned long long seed,
                       long long mesh_triangles) {
  JsonObject j;
  j.text("species", species);
  j.integer("seed", seed);
  j.integers("stems_per_level", st.stems_per_level);
  j.integer("stems", st.stems())
      .integer("leaves", st.leaves)
      .integer("curve_segments", st.curve_segments);
  j.integer("triangles", st.triangles).integer("leaf_triangles", st.leaf_triangles);
  j.integer("skeleton_segments", st.skeleton_segments).integer("points", st.points);
  j.number("height", st.height, 6)
      .number("crown_width", st.crown_width, 6)
      .number("seconds", st.seconds, 6);
  if (st.has_geometry) {
    const GeometryStats& g = st.geometry;
    auto size = [&](const char* key, std::size_t v) { j.integer(key, static_cast<long long>(v)); };
    size("limbs", g.limbs);
    size("grids", g.grids);
    size("grid_vertices", g.grid_vertices);
    size("grid_triangles", g.grid_triangles);
    size("leaf_cards", g.leaf_cards);
    size("tension_raised_limbs", g.tension_raised_limbs);
    size("ramiform_forks", g.ramiform_forks);
    size("ramiforms", g.ramiforms);
    size("ramiform_triangles", g.ramiform_triangles);
    size("ramiform_trunk_forks", g.ramiform_trunk_forks);
    size("ramiform_trunk_collars", g.ramiform_trunk_collars);
    // Only a build knows these (a count for --stats alone does not build, issue 31).
    if (g.built) {
      size("radius_adjusted_segments", g.radius_adjusted_segments);
      size("geometry_bytes", g.bytes);
    }
    j.number("geometry_seconds", st.geometry_seconds, 6);
  }
  if (mesh_triangles >= 0) j.integer("mesh_triangles", mesh_triangles);
  return j.str() + "\n";
}

std::string stats_text(const TreeStats& st) {
  std::string levels;
  for (size_t i = 0; i < st.stems_per_level.size(); ++i) {
    levels += (i ? " / " : "") + std::to_string(st.stems_per_level[i]);
  }
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "stems          %lld (per level %s)\nleaves         %lld\n"
                "curve segments %lld\ntriangles      %lld (leaves %lld)\nheight         %.2f m\n"
                "crown width    %.2f m\ngrown in       %.3f s\n",
                st.stems(), levels.c_str(), st.leaves, st.curve_segments, st.triangles,
                st.leaf_triangles, st.height, st.crown_width, st.seconds);
  std::string out = buf;
  if (st.has_geometry) {
    const GeometryStats& g = st.geometry;
    if (g.built) {
      std::snprintf(buf, sizeof buf,
                    "limbs          %zu (tension raised on %zu; radius reduced on %zu curve "
                    "segments)\ntrunk grids    %zu (%zu vertices, %zu triangles)\n"
                    "geometry       %.1f MB, built in %.3f s\n",
                    g.limbs, g.tension_raised_limbs, g.radius_adjusted_segments, g.grids,
                    g.grid_vertices, g.grid_triangles, g.bytes / 1e6, st.geometry_seconds);
    } else {
      std::snprintf(buf, sizeof buf,
                    "limbs          %zu (tension raised on %zu)\n"
                    "trunk grids    %zu (%zu vertices, %zu triangles)\n"
                    "geometry       counted in %.3f s (not built; -o builds it)\n",
                    g.limbs, g.tension_raised_limbs, g.grids, g.grid_vertices, g.grid_triangles,
                    st.geometry_seconds);
    }
    out += buf;
    if (g.ramiform_forks > 0) {
      std::snprintf(buf, sizeof buf,
                    "ramiforms      %zu collars at %zu forks (the trunk's: %zu of %zu), %zu "
                    "triangles\n",
                    g.ramiforms, g.ramiform_forks, g.ramiform_trunk_collars, g.ramiform_trunk_forks,
                    g.ramiform_triangles);
      out += buf;
    }
  }
  return out;
}

}  // namespace arbor::generator
