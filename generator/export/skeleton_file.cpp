// Skeleton file writer: points and connections, the format formats/skeleton_file.cpp reads.
#include "generator/export/skeleton_file.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "generator/export/text_output.h"

namespace arbor::generator {

namespace {
void put(std::string& out, float v) { put_number(out, v); }
}  // namespace

void write_skeleton_file(const Skeleton& sk, const std::string& path) {
  // Point ids: every skeleton point, except a stem's first point when it is its parent's point.
  std::vector<std::vector<int>> ids(sk.stems.size());
  int next = 0;
  std::string out = "# arbor skeleton: points and connections (docs/skeleton-format.md)\n";
  out += "trunk ";
  put(out, sk.trunk.flare);
  out += " " + std::to_string(sk.trunk.lobes) + " ";
  put(out, sk.trunk.lobe_depth);
  out += "\n";
  auto point = [&](const SkeletonPoint& p) {
    out += "point " + std::to_string(next) + " ";
    put(out, p.position.x);
    out += ' ';
    put(out, p.position.y);
    out += ' ';
    put(out, p.position.z);
    out += ' ';
    put(out, p.radius);
    out += '\n';
    return next++;
  };
  for (std::size_t s = 0; s < sk.stems.size(); ++s) {
    const Stem& st = sk.stems[s];
    for (std::uint32_t k = 0; k < st.point_count; ++k) {
      if (k == 0 && st.parent >= 0 && st.parent_point >= 0) {
        ids[s].push_back(ids[static_cast<size_t>(st.parent)][static_cast<size_t>(st.parent_point)]);
      } else {
        ids[s].push_back(point(sk.points[st.first_point + k]));
      }
    }
  }
  for (std::size_t s = 0; s < sk.stems.size(); ++s) {
    const Stem& st = sk.stems[s];
    if (st.parent >= 0 && st.parent_point < 0) {
      // Starts between two of the parent's points: on the segment holding its offset.
      const Stem& p = sk.stems[static_cast<size_t>(st.parent)];
      const double z = p.length > 0.0f ? st.parent_offset / p.length : 0.0;
      const double f =
          std::clamp((z - p.z_start) / std::max(1e-9, 1.0 - double(p.z_start)), 0.0, 1.0) *
          (p.point_count - 1);
      const auto j = static_cast<std::uint32_t>(std::min(std::floor(f), p.point_count - 2.0));
      out += "branch " + std::to_string(ids[s][0]) + " on " +
             std::to_string(ids[static_cast<size_t>(st.parent)][j]) + " " +
             std::to_string(ids[static_cast<size_t>(st.parent)][j + 1]) + " ";
      put(out, static_cast<float>(f - j));
      out += '\n';
    }
    for (std::uint32_t k = 1; k < st.point_count; ++k) {
      out += "connect " + std::to_string(ids[s][k - 1]) + " " + std::to_string(ids[s][k]) + "\n";
    }
    out += "stem " + std::to_string(ids[s][1]) + " level " + std::to_string(st.level) + " clone " +
           std::to_string(st.is_clone ? 1 : 0) + " taper ";
    put(out, st.taper);
    out += " radius ";
    put(out, st.base_radius);
    out += " length ";
    put(out, st.length);
    out += " zstart ";
    put(out, st.z_start);
    out += " offset ";
    put(out, st.parent >= 0 ? st.parent_offset : -1.0f);
    out += " start ";
    put(out, sk.points[st.first_point].radius);
    if (st.color != glm::vec3(1.0f)) {
      out += " red ";
      put(out, st.color.x);
      out += " green ";
      put(out, st.color.y);
      out += " blue ";
      put(out, st.color.z);
    }
    out += '\n';
  }
  for (const Leaf& l : sk.leaves) {
    out += "leaf " + std::to_string(ids[static_cast<size_t>(l.stem)][1]);
    for (float v : {l.position.x, l.position.y, l.position.z, l.axis.x, l.axis.y, l.axis.z,
                    l.normal.x, l.normal.y, l.normal.z, l.length, l.width}) {
      out += ' ';
      put(out, v);
    }
    out += " " + std::to_string(l.shape) + "\n";
  }
  for (const LeafTriangle& t : sk.leaf_triangles) {
    out += "leaftri " + std::to_string(ids[static_cast<size_t>(t.stem)][1]) + " " +
           std::to_string(t.leaf);
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) {
        out += ' ';
        put(out, t.v[k][c]);
      }
    }
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      put(out, t.color[c]);
    }
    out += '\n';
  }
  for (const LeafLine& l : sk.leaf_lines) {
    out += "leafline " + std::to_string(ids[static_cast<size_t>(l.stem)][1]) + " " +
           std::to_string(l.leaf);
    for (float v :
         {l.a.x, l.a.y, l.a.z, l.b.x, l.b.y, l.b.z, l.radius, l.color.x, l.color.y, l.color.z}) {
      out += ' ';
      put(out, v);
    }
    out += '\n';
  }
  AtomicFile file(path);
  file.write(out);
  file.commit();
}

}  // namespace arbor::generator
