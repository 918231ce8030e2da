// Skeleton file reader.
#include "formats/skeleton_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include <glm/geometric.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "generator/export/text_output.h"

namespace arbor::formats {

namespace {

struct PointRecord {
  glm::vec3 position{0.0f};
  float radius = 0.0f;
  int line = 0;
  int incoming = -1;  // the point it is connected from
  int incoming_line = 0;
  std::vector<int> outgoing;  // in file order
  bool branch = false;        // starts a limb between two other points
  int branch_a = -1, branch_b = -1;
  float branch_t = 0.0f;
};

struct StemRecord {
  int level = -1;
  bool clone = false;
  float taper = -1.0f, base_radius = 0.0f, length = 0.0f, z_start = 0.0f;
  float offset = -1.0f;   // metres along the parent where it starts; -1: computed
  glm::vec3 color{1.0f};  // multiplies the bark albedo
  float start = -1.0f;    // radius of the stem's own first point (a shared branch point has the
                          // parent's radius in the file); -1: the point's
  int line = 0;
};

class Reader {
 public:
  Reader(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  generator::Skeleton read() {
    std::istringstream in(text_);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      tokens_.clear();
      columns_.clear();
      split(line);
      if (tokens_.empty()) continue;
      line_ = number;
      record();
    }
    return build();
  }

 private:
  [[noreturn]] void fail(std::size_t token, const std::string& message) const {
    throw InputError({path_, line_, token < columns_.size() ? columns_[token] : 1}, message);
  }
  void split(const std::string& line) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > start) {
        tokens_.push_back(line.substr(start, i - start));
        columns_.push_back(static_cast<int>(start) + 1);
      }
    }
  }
  double real(std::size_t k) const {
    if (k >= tokens_.size()) fail(tokens_.size(), "'" + tokens_[0] + "' needs more values");
    double v = 0.0;
    const std::string& t = tokens_[k];
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) fail(k, "'" + t + "' is not a number");
    if (!std::isfinite(v)) fail(k, "'" + t + "' is not a finite number");
    // Positions and sizes in metres: past 1000 km the float arithmetic of splines overflows.
    if (std::fabs(v) > 1e6) fail(k, "'" + t + "' is out of range [-1e6, 1e6]");
    return v;
  }
  int id(std::size_t k) const {
    const double v = real(k);
    if (v != std::floor(v) || v < 0 || v > 1e9) fail(k, "'" + tokens_[k] + "' is not a point id");
    return static_cast<int>(v);
  }
  int known(std::size_t k) const {
    const int i = id(k);
    if (!points_.count(i))
      fail(k, "point " + std::to_string(i) + " is not defined (before this line)");
    return i;
  }
  void count(std::size_t lo, std::size_t hi) const {
    if (tokens_.size() < lo || tokens_.size() > hi) {
      fail(0, "'" + tokens_[0] + "' takes " +
                  (lo == hi ? std::to_string(lo - 1)
                            : std::to_string(lo - 1) + " to " + std::to_string(hi - 1)) +
                  " values");
    }
  }

  void record() {
    const std::string& kind = tokens_[0];
    if (kind == "point") {
      count(5, 6);
      const int i = id(1);
      if (points_.count(i))
        fail(1, "point " + std::to_string(i) + " is defined twice (first on line " +
                    std::to_string(points_[i].line) + ")");
      PointRecord p;
      p.position = glm::vec3(real(2), real(3), real(4));
      p.radius = tokens_.size() > 5 ? static_cast<float>(real(5)) : default_radius_;
      if (p.radius < 0.0f) fail(5, "a radius must not be negative");
      p.line = line_;
      points_[i] = p;
      order_.push_back(i);
    } else if (kind == "connect") {
      count(3, 3);
      const int a = known(1), b = known(2);
      if (a == b) fail(2, "point " + std::to_string(a) + " is connected to itself");
      incoming(b, a, 2);
      points_[a].outgoing.push_back(b);
    } else if (kind == "branch") {
      // branch C on A B T: point C starts a limb on the segment A→B at fraction T.
      count(6, 6);
      const int c = known(1);
      if (tokens_[2] != "on") fail(2, "expected 'on': branch C on A B T");
      const int a = known(3), b = known(4);
      const double t = real(5);
      if (t < 0.0 || t > 1.0) fail(5, "the fraction along the segment must be in [0, 1]");
      incoming(c, a, 1);
      PointRecord& p = points_[c];
      p.branch = true;
      p.branch_a = a;
      p.branch_b = b;
      p.branch_t = static_cast<float>(t);
    } else if (kind == "stem") {
      // stem P level L clone C taper T radius R length S zstart Z offset O: the stem whose second
      // point is P (each point has one incoming limb, so P names one stem).
      if (tokens_.size() < 2 || tokens_.size() % 2 != 0)
        fail(0, "stem P followed by name value pairs");
      const int p = known(1);
      StemRecord s;
      s.line = line_;
      for (std::size_t k = 2; k + 1 < tokens_.size(); k += 2) {
        const std::string& key = tokens_[k];
        const double v = real(k + 1);
        if (key == "level")
          s.level = static_cast<int>(v);
        else if (key == "clone")
          s.clone = v != 0.0;
        else if (key == "taper")
          s.taper = static_cast<float>(v);
        else if (key == "radius")
          s.base_radius = static_cast<float>(v);
        else if (key == "length")
          s.length = static_cast<float>(v);
        else if (key == "zstart")
          s.z_start = static_cast<float>(v);
        else if (key == "offset")
          s.offset = static_cast<float>(v);
        else if (key == "start")
          s.start = static_cast<float>(v);
        else if (key == "red")
          s.color.x = static_cast<float>(v);
        else if (key == "green")
          s.color.y = static_cast<float>(v);
        else if (key == "blue")
          s.color.z = static_cast<float>(v);
        else
          fail(k, "unknown stem property '" + key + "'");
      }
      stems_[p] = s;
    } else if (kind == "leaf") {
      count(14, 14);
      const int p = known(1);
      generator::Leaf l;
      l.position = glm::vec3(real(2), real(3), real(4));
      l.axis = glm::vec3(real(5), real(6), real(7));
      l.normal = glm::vec3(real(8), real(9), real(10));
      l.length = static_cast<float>(real(11));
      l.width = static_cast<float>(real(12));
      l.shape = static_cast<std::int32_t>(real(13));
      if (glm::length(l.axis) < 1e-6f || glm::length(l.normal) < 1e-6f)
        fail(5, "a leaf needs a non-zero axis and normal");
      if (l.length <= 0.0f || l.width <= 0.0f) fail(11, "a leaf needs a positive length and width");
      if (l.shape < 0 || l.shape > 5) fail(13, "leaf shapes are 0 to 5");
      leaves_.emplace_back(p, l);
    } else if (kind == "leaftri" || kind == "leafline") {
      // leaftri P LEAF x y z x y z x y z R G B / leafline P LEAF x y z x y z RADIUS R G B
      const bool tri = kind == "leaftri";
      count(tri ? 15 : 13, tri ? 15 : 13);
      const int p = known(1);
      const int leaf = static_cast<int>(real(2));
      if (tri) {
        generator::LeafTriangle t;
        for (int k = 0; k < 3; ++k)
          t.v[k] = glm::vec3(real(3 + 3 * k), real(4 + 3 * k), real(5 + 3 * k));
        t.color = glm::vec3(real(12), real(13), real(14));
        t.leaf = leaf;
        free_triangles_.emplace_back(p, t);
      } else {
        generator::LeafLine l;
        l.a = glm::vec3(real(3), real(4), real(5));
        l.b = glm::vec3(real(6), real(7), real(8));
        l.radius = static_cast<float>(real(9));
        l.color = glm::vec3(real(10), real(11), real(12));
        l.leaf = leaf;
        if (l.radius <= 0.0f) fail(9, "a line needs a positive radius");
        free_lines_.emplace_back(p, l);
      }
    } else if (kind == "trunk") {
      count(4, 4);
      trunk_.flare = static_cast<float>(real(1));
      trunk_.lobes = static_cast<std::int32_t>(real(2));
      trunk_.lobe_depth = static_cast<float>(real(3));
    } else if (kind == "radius") {
      count(2, 2);
      default_radius_ = static_cast<float>(real(1));
      if (default_radius_ < 0.0f) fail(1, "a radius must not be negative");
    } else {
      fail(0,
           "unknown record '" + kind +
               "' (known: point, connect, branch, stem, leaf, leaftri, leafline, trunk, radius)");
    }
  }

  void incoming(int to, int from, std::size_t token) {
    PointRecord& p = points_[to];
    if (p.incoming >= 0) {
      fail(token, "point " + std::to_string(to) + " already has an incoming limb (from point " +
                      std::to_string(p.incoming) + "); Bloomenthal's skeleton allows one");
    }
    p.incoming = from;
    p.incoming_line = line_;
  }

  generator::Skeleton build() {
    if (points_.empty()) throw InputError({path_, 1, 1}, "the skeleton has no points");
    std::vector<int> roots;
    for (int i : order_) {
      if (points_[i].incoming < 0) roots.push_back(i);
    }
    if (roots.size() != 1) {
      std::string list;
      for (std::size_t k = 0; k < roots.size() && k < 5; ++k)
        list += (k ? ", " : "") + std::to_string(roots[k]);
      throw InputError({path_, roots.empty() ? 1 : points_[roots[1]].line, 1},
                       "the skeleton must have exactly one root (a point with no incoming limb); "
                       "it has " +
                           std::to_string(roots.size()) +
                           (roots.empty() ? "" : ": points " + list));
    }
    // Stems: the first outgoing connection of a point continues its stem; others start stems.
    generator::Skeleton sk;
    sk.trunk = trunk_;
    std::vector<int> reached;
    build_stems(sk, roots[0], reached);
    std::sort(reached.begin(), reached.end());
    for (int i : order_) {
      if (!std::binary_search(reached.begin(), reached.end(), i)) {
        throw InputError(
            {path_, points_[i].line, 1},
            "point " + std::to_string(i) + " is not connected to the root (all points must be)");
      }
    }
    keep_file_order(sk);
    for (const auto& [p, leaf] : leaves_) {
      const auto it = stem_of_point_.find(p);
      if (it == stem_of_point_.end())
        throw InputError({path_, 1, 1},
                         "a leaf names point " + std::to_string(p) + ", which is on no stem");
      generator::Leaf l = leaf;
      // Hand-written frames may be any length; arbor's own are unit already (kept bit for bit).
      if (std::fabs(glm::length(l.axis) - 1.0f) > 1e-5f) l.axis = glm::normalize(l.axis);
      if (std::fabs(glm::length(l.normal) - 1.0f) > 1e-5f) l.normal = glm::normalize(l.normal);
      l.stem = it->second;
      sk.leaves.push_back(l);
    }
    for (auto [p, t] : free_triangles_) {
      t.stem = stem_on(p);
      sk.leaf_triangles.push_back(t);
    }
    for (auto [p, l] : free_lines_) {
      l.stem = stem_on(p);
      sk.leaf_lines.push_back(l);
    }
    int levels = 1;
    for (const generator::Stem& s : sk.stems) levels = std::max(levels, s.level + 1);
    sk.levels = levels;
    const std::string problem = generator::validate(sk);
    if (!problem.empty()) throw InputError({path_, 1, 1}, problem);
    return sk;
  }

  int stem_on(int point) const {
    const auto it = stem_of_point_.find(point);
    if (it == stem_of_point_.end()) {
      throw InputError({path_, 1, 1}, "a leaf element names point " + std::to_string(point) +
                                          ", which is on no stem");
    }
    return it->second;
  }

  // Orders stems as the file lists them (by the line of the connection into each stem's second
  // point), when that keeps every parent before its children; otherwise depth-first order stays.
  void keep_file_order(generator::Skeleton& sk) {
    const std::size_t n = sk.stems.size();
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return stem_lines_[a] < stem_lines_[b]; });
    std::vector<int> new_index(n);
    for (std::size_t i = 0; i < n; ++i) new_index[order[i]] = static_cast<int>(i);
    for (std::size_t i = 0; i < n; ++i) {
      const int parent = sk.stems[order[i]].parent;
      if (parent >= 0 && new_index[static_cast<size_t>(parent)] >= static_cast<int>(i)) return;
    }
    std::vector<generator::Stem> sorted(n);
    for (std::size_t i = 0; i < n; ++i) {
      sorted[i] = sk.stems[order[i]];
      if (sorted[i].parent >= 0)
        sorted[i].parent = new_index[static_cast<size_t>(sorted[i].parent)];
    }
    sk.stems = std::move(sorted);
    for (auto& [point, stem] : stem_of_point_) stem = new_index[static_cast<size_t>(stem)];
  }

  // Where a stem starts: at `first` (a point of `parent`, index `parent_point` along it, or a
  // branch record when parent_point is -1), continuing to `second_hint` when given.
  struct StemStart {
    int parent, parent_point, first, second_hint;
  };

  // Builds every stem, parents before children, in depth-first order (each stem's children in
  // file order). Iterative with an explicit stack, so a skeleton nested thousands of levels
  // deep cannot overflow the call stack; linear in the number of points and records.
  void build_stems(generator::Skeleton& sk, int root, std::vector<int>& reached) {
    // Branch records by the segment they start on, in file order.
    std::map<std::pair<int, int>, std::vector<int>> on_segment;
    for (int c : order_) {
      const PointRecord& pc = points_[c];
      if (pc.branch) on_segment[{pc.branch_a, pc.branch_b}].push_back(c);
    }
    std::vector<StemStart> pending{{-1, -1, root, -1}};
    std::vector<StemStart> children;
    while (!pending.empty()) {
      const StemStart next = pending.back();
      pending.pop_back();
      children.clear();
      add_stem(sk, next, on_segment, reached, children);
      pending.insert(pending.end(), children.rbegin(), children.rend());
    }
  }

  // Builds one stem and lists, in order, the stems that start on it.
  void add_stem(generator::Skeleton& sk, const StemStart& from,
                const std::map<std::pair<int, int>, std::vector<int>>& on_segment,
                std::vector<int>& reached, std::vector<StemStart>& children) {
    const int parent = from.parent, parent_point = from.parent_point, first = from.first;
    std::vector<int> chain{first};
    int at = from.second_hint >= 0
                 ? from.second_hint
                 : (points_[first].outgoing.empty() ? -1 : points_[first].outgoing[0]);
    while (at >= 0) {
      // A point that a `stem` record names starts a stem of its own (e.g. a parent that ends
      // where its branches begin); otherwise the first outgoing limb continues this stem.
      if (chain.size() >= 2 && stems_.count(at)) break;
      chain.push_back(at);
      at = points_[at].outgoing.empty() ? -1 : points_[at].outgoing[0];
    }
    if (chain.size() < 2) {
      throw InputError({path_, points_[first].line, 1},
                       "point " + std::to_string(first) + " starts a limb that goes nowhere");
    }
    for (std::size_t k = 1; k < chain.size(); ++k) {
      const PointRecord& a = points_[chain[k - 1]];
      const PointRecord& b = points_[chain[k]];
      if (glm::length(a.position - b.position) < 1e-6f) {
        // A limb segment of length 0 has no direction: splines and frames through it are NaN.
        throw InputError({path_, b.incoming_line > 0 ? b.incoming_line : b.line, 1},
                         "points " + std::to_string(chain[k - 1]) + " and " +
                             std::to_string(chain[k]) +
                             " are at the same position (closer than 1 micrometre), so the limb "
                             "between them has no direction");
      }
    }
    generator::Stem st;
    st.parent = parent;
    st.parent_point = parent_point;
    st.first_point = static_cast<std::uint32_t>(sk.points.size());
    st.point_count = static_cast<std::uint32_t>(chain.size());
    float length = 0.0f;
    for (std::size_t k = 0; k < chain.size(); ++k) {
      sk.points.push_back({points_[chain[k]].position, points_[chain[k]].radius});
      if (k > 0) length += glm::length(points_[chain[k]].position - points_[chain[k - 1]].position);
    }
    st.length = length;
    st.base_radius = points_[first].radius;
    st.level = parent < 0 ? 0 : sk.stems[static_cast<size_t>(parent)].level + 1;
    const auto rec = stems_.find(chain[1]);
    if (rec != stems_.end()) {
      const StemRecord& r = rec->second;
      if (r.level >= 0) st.level = r.level;
      st.is_clone = r.clone;
      st.taper = r.taper;
      if (r.length > 0.0f) st.length = r.length;
      if (r.base_radius > 0.0f) st.base_radius = r.base_radius;
      st.z_start = r.z_start;
      if (r.start >= 0.0f) sk.points[st.first_point].radius = r.start;
      st.color = r.color;
    }
    if (parent >= 0) {
      if (rec != stems_.end() && rec->second.offset >= 0.0f) {
        st.parent_offset = rec->second.offset;
      } else if (parent_point >= 0) {
        st.parent_offset =
            arc_to_point_[static_cast<size_t>(parent)][static_cast<size_t>(parent_point)];
      }
    }
    const auto index = static_cast<int>(sk.stems.size());
    sk.stems.push_back(st);
    // Arc length from the base of the whole stem to each of its points, summed point by point.
    std::vector<float> arc(chain.size());
    arc[0] = st.z_start * st.length;
    for (std::size_t k = 1; k < chain.size(); ++k) {
      arc[k] = arc[k - 1] + glm::length(sk.points[st.first_point + k].position -
                                        sk.points[st.first_point + k - 1].position);
    }
    arc_to_point_.push_back(std::move(arc));
    stem_lines_.push_back(points_[chain[1]].incoming_line);
    for (std::size_t k = 1; k < chain.size(); ++k) stem_of_point_[chain[k]] = index;
    if (parent < 0) stem_of_point_[first] = index;
    reached.insert(reached.end(), chain.begin(), chain.end());
    // Children: other outgoing connections at each point of this stem, then branch records on
    // its segments, in file order.
    for (std::size_t k = 0; k < chain.size(); ++k) {
      // A first point shared with the parent: its other limbs are the parent's children.
      if (k == 0 && parent_point >= 0) continue;
      for (int o : points_[chain[k]].outgoing) {
        if (k + 1 < chain.size() && o == chain[k + 1]) continue;  // the continuation
        children.push_back({index, static_cast<int>(k), chain[k], o});
      }
    }
    std::vector<std::pair<int, int>> branches;  // (line, point)
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
      const auto it = on_segment.find({chain[k], chain[k + 1]});
      if (it == on_segment.end()) continue;
      for (int c : it->second) branches.emplace_back(points_[c].line, c);
    }
    std::sort(branches.begin(), branches.end());
    for (const auto& [line, c] : branches) children.push_back({index, -1, c, -1});
  }

  const std::string& text_;
  std::string path_;
  int line_ = 0;
  std::vector<std::string> tokens_;
  std::vector<int> columns_;
  std::map<int, PointRecord> points_;
  std::vector<int> order_;
  std::map<int, StemRecord> stems_;
  std::vector<std::pair<int, generator::Leaf>> leaves_;
  std::vector<std::pair<int, generator::LeafTriangle>> free_triangles_;
  std::vector<std::pair<int, generator::LeafLine>> free_lines_;
  std::map<int, int> stem_of_point_;
  std::vector<int> stem_lines_;  // per stem (depth-first index): line of its first connection
  std::vector<std::vector<float>> arc_to_point_;  // per stem: arc length to each of its points
  generator::TrunkDisplacement trunk_;
  float default_radius_ = 0.0f;
};

}  // namespace

generator::Skeleton parse_skeleton_file(const std::string& text, const std::string& path) {
  return Reader(text, path).read();
}

}  // namespace arbor::formats
