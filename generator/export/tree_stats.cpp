// Statistics of a Skeleton.
#include "generator/export/tree_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/json.h"
#include "generator/geometry/leaf_shapes.h"

namespace arbor::gen {

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
  const glm::vec3 axis = sk.stems.empty() ? glm::vec3(0.0f)
                                          : sk.points[sk.stems.front().first_point].position;
  double reach = 0.0, top = 0.0;
  auto visit = [&](const glm::vec3& p, double margin) {
    top = std::max(top, static_cast<double>(p.z) + margin);
    reach = std::max(reach, std::hypot(p.x - axis.x, p.y - axis.y) + margin);
  };
  for (const SkeletonPoint& p : sk.points) visit(p.position, p.radius);
  const auto& shapes = leaf_shapes();
  for (const Leaf& l : sk.leaves) {
    st.leaf_triangles += static_cast<long long>(shapes[static_cast<size_t>(l.shape)].triangles.size());
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
  st.leaf_triangles = static_cast<long long>(g.leaf_triangles);
  st.triangles = static_cast<long long>(g.leaf_triangles + g.grid_triangles);
}

std::string stats_json(const TreeStats& st, const std::string& species, unsigned long long seed,
                       long long mesh_triangles) {
  std::string out = "{\"species\": \"" + json_escape(species);
  out += "\", \"seed\": " + std::to_string(seed) + ", \"stems_per_level\": [";
  for (size_t i = 0; i < st.stems_per_level.size(); ++i) {
    out += (i ? ", " : "") + std::to_string(st.stems_per_level[i]);
  }
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "], \"stems\": %lld, \"leaves\": %lld, \"curve_segments\": %lld, "
                "\"triangles\": %lld, \"leaf_triangles\": %lld, \"skeleton_segments\": %lld, "
                "\"points\": %lld, \"height\": %.6g, \"crown_width\": %.6g, \"seconds\": %.6g",
                st.stems(), st.leaves, st.curve_segments, st.triangles, st.leaf_triangles,
                st.skeleton_segments, st.points, st.height, st.crown_width, st.seconds);
  out += buf;
  if (st.has_geometry) {
    const GeometryStats& g = st.geometry;
    std::snprintf(buf, sizeof buf,
                  ", \"limbs\": %zu, \"grids\": %zu, \"grid_vertices\": %zu, "
                  "\"grid_triangles\": %zu, \"tension_raised_limbs\": %zu, "
                  "\"radius_adjusted_segments\": %zu, \"geometry_bytes\": %zu, "
                  "\"geometry_seconds\": %.6g",
                  g.limbs, g.grids, g.grid_vertices, g.grid_triangles, g.tension_raised_limbs,
                  g.radius_adjusted_segments, g.bytes, st.geometry_seconds);
    out += buf;
  }
  if (mesh_triangles >= 0) out += ", \"mesh_triangles\": " + std::to_string(mesh_triangles);
  out += "}\n";
  return out;
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
    std::snprintf(buf, sizeof buf,
                  "limbs          %zu (tension raised on %zu; radius reduced on %zu curve "
                  "segments)\ntrunk grids    %zu (%zu vertices, %zu triangles)\n"
                  "geometry       %.1f MB, built in %.3f s\n",
                  g.limbs, g.tension_raised_limbs, g.radius_adjusted_segments, g.grids,
                  g.grid_vertices, g.grid_triangles, g.bytes / 1e6, st.geometry_seconds);
    out += buf;
  }
  return out;
}

}  // namespace arbor::gen
