// OBJ reader: one pass over the lines, linear in the file, every error positioned.
#include "formats/obj_mesh.h"

#include <charconv>
#include <cmath>

#include "common/error.h"
#include "common/input_file.h"
#include "generator/species.h"
#include "formats/species_file.h"

namespace arbor::formats {

namespace {

class ObjReader {
 public:
  ObjReader(std::string_view text, std::string path) : text_(text), path_(std::move(path)) {}

  ObjMesh read() {
    std::size_t start = 0;
    while (start <= text_.size()) {
      std::size_t end = text_.find('\n', start);
      if (end == std::string_view::npos) end = text_.size();
      ++line_;
      line_start_ = start;
      statement(text_.substr(start, end - start));
      start = end + 1;
    }
    check_forward_references();
    if (!mesh_.normals.empty()) mesh_.normal_indices = std::move(triangle_normals_);
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(std::string_view at, const std::string& message) const {
    const auto column =
        static_cast<int>(at.data() - text_.data() - static_cast<std::ptrdiff_t>(line_start_)) + 1;
    throw InputError({path_, line_, column}, message);
  }

  // The next white-space separated token of `rest`, which moves past it; empty at the end.
  static std::string_view token(std::string_view& rest) {
    std::size_t i = 0;
    while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t' || rest[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < rest.size() && rest[j] != ' ' && rest[j] != '\t' && rest[j] != '\r') ++j;
    const std::string_view t = rest.substr(i, j - i);
    rest.remove_prefix(j);
    return t;
  }

  static std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
      s.remove_suffix(1);
    return s;
  }

  double number(std::string_view t) const {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size())
      fail(t, "'" + std::string(t) + "' is not a number");
    if (!std::isfinite(v)) fail(t, "'" + std::string(t) + "' is not a finite number");
    return v;
  }

  // `count` to `most` numbers, the rest of the line; returns how many there were.
  int numbers(std::string_view rest, std::string_view keyword, int count, int most,
              double* out) const {
    int n = 0;
    for (std::string_view t = token(rest); !t.empty(); t = token(rest)) {
      if (n == most)
        fail(t,
             "'" + std::string(keyword) + "' takes at most " + std::to_string(most) + " numbers");
      out[n++] = number(t);
    }
    if (n < count)
      fail(keyword, "'" + std::string(keyword) + "' needs " + std::to_string(count) + " numbers");
    return n;
  }

  // One index of a face corner: 1-based, or negative counting back from the last defined.
  // Returns it 0-based; a positive index past what is defined so far is checked at the end.
  std::int64_t index(std::string_view t, std::string_view corner, std::size_t defined,
                     const char* what) {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || v == 0 ||
        v > static_cast<std::int64_t>(UINT32_MAX) || v < -static_cast<std::int64_t>(UINT32_MAX)) {
      fail(t, "'" + std::string(corner) + "': '" + std::string(t) + "' is not a " + what +
                  " index (1, 2, … or -1, -2, …)");
    }
    if (v < 0) {
      if (static_cast<std::uint64_t>(-v) > defined) {
        fail(t, "'" + std::string(corner) + "' refers to " + what + " " + std::to_string(v) +
                    ", but only " + std::to_string(defined) + " are defined before it");
      }
      return static_cast<std::int64_t>(defined) + v;
    }
    if (static_cast<std::uint64_t>(v) > defined) forward_.push_back({line_, t.data(), v - 1, what});
    return v - 1;
  }

  void face(std::string_view rest, std::string_view keyword) {
    corners_.clear();
    corner_normals_.clear();
    for (std::string_view corner = token(rest); !corner.empty(); corner = token(rest)) {
      // v, v/vt, v//vn or v/vt/vn
      std::string_view parts[3];
      int n = 0;
      std::string_view r = corner;
      for (;;) {
        const std::size_t slash = r.find('/');
        if (n == 2 && slash != std::string_view::npos)
          fail(corner, "'" + std::string(corner) + "' has more than v/vt/vn");
        parts[n++] = r.substr(0, slash);
        if (slash == std::string_view::npos) break;
        r.remove_prefix(slash + 1);
      }
      corners_.push_back(
          static_cast<std::uint32_t>(index(parts[0], corner, mesh_.positions.size(), "vertex")));
      if (n > 1 && !parts[1].empty()) index(parts[1], corner, texcoords_, "texture coordinate");
      corner_normals_.push_back(
          n > 2 ? static_cast<std::uint32_t>(index(parts[2], corner, normals_, "normal"))
                : ObjMesh::kNoNormal);
    }
    if (corners_.size() < 3) fail(keyword, "a face needs at least three vertices");
    if (part_dirty_) {
      mesh_.parts.push_back(current_);
      mesh_.part_line.push_back(line_);
      part_dirty_ = false;
    }
    const auto part = static_cast<std::uint32_t>(mesh_.parts.size() - 1);
    for (std::size_t k = 1; k + 1 < corners_.size(); ++k) {
      mesh_.indices.insert(mesh_.indices.end(), {corners_[0], corners_[k], corners_[k + 1]});
      mesh_.part.push_back(part);
      triangle_normals_.insert(triangle_normals_.end(),
                               {corner_normals_[0], corner_normals_[k], corner_normals_[k + 1]});
    }
  }

  void statement(std::string_view line) {
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    std::string_view rest = line;
    const std::string_view keyword = token(rest);
    if (keyword.empty()) return;
    double v[7];
    if (keyword == "v") {
      // x y z, optionally w, or x y z r g b (vertex colours).
      numbers(rest, keyword, 3, 7, v);
      // Beyond a million kilometres the float positions of the geometry lose all meaning.
      std::string_view coordinate = rest;
      for (int k = 0; k < 3; ++k) {
        const std::string_view t = token(coordinate);
        if (std::fabs(v[k]) > 1e9) fail(t, "'" + std::string(t) + "' is out of range [-1e9, 1e9]");
      }
      mesh_.positions.emplace_back(v[0], v[1], v[2]);
    } else if (keyword == "vt") {
      numbers(rest, keyword, 1, 3, v);
      ++texcoords_;
    } else if (keyword == "vn") {
      numbers(rest, keyword, 3, 3, v);
      const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(length > 1e-12) || !std::isfinite(length))
        fail(keyword, "a vertex normal of zero length");
      mesh_.normals.emplace_back(v[0] / length, v[1] / length, v[2] / length);
      ++normals_;
    } else if (keyword == "f") {
      face(rest, keyword);
    } else if (keyword == "g" || keyword == "o") {
      current_.group = std::string(trimmed(rest));
      part_dirty_ = true;
    } else if (keyword == "usemtl") {
      current_.material = std::string(trimmed(rest));
      part_dirty_ = true;
    } else if (keyword == "mtllib" || keyword == "s" || keyword == "l" || keyword == "p" ||
               keyword == "vp") {
      // Material libraries (materials come from the scene), smoothing groups, lines, points
      // and parameter-space vertices have nothing to render.
    } else {
      fail(keyword, "unknown OBJ statement '" + std::string(keyword) + "'");
    }
  }

  // Positive indices may name elements defined later in the file; they must exist by its end.
  void check_forward_references() const {
    for (const Forward& f : forward_) {
      const std::size_t defined = f.what[0] == 'v'   ? mesh_.positions.size()
                                  : f.what[0] == 't' ? texcoords_
                                                     : normals_;
      if (static_cast<std::uint64_t>(f.index) >= defined) {
        const auto column =
            static_cast<int>(f.at - text_.data()) - static_cast<int>(line_offset(f.line)) + 1;
        throw InputError({path_, f.line, column}, std::string("a face refers to ") + f.what + " " +
                                                      std::to_string(f.index + 1) +
                                                      ", but the file defines " +
                                                      std::to_string(defined));
      }
    }
  }

  std::size_t line_offset(int line) const {
    std::size_t at = 0;
    for (int l = 1; l < line; ++l) at = text_.find('\n', at) + 1;
    return at;
  }

  struct Forward {
    int line;
    const char* at;
    std::int64_t index;  // 0-based
    const char* what;
  };

  std::string_view text_;
  std::string path_;
  int line_ = 0;
  std::size_t line_start_ = 0;
  ObjMesh mesh_;
  ObjMesh::Part current_;
  bool part_dirty_ = true;
  std::size_t texcoords_ = 0, normals_ = 0;
  std::vector<std::uint32_t> corners_, corner_normals_, triangle_normals_;
  std::vector<Forward> forward_;
};

}  // namespace

ObjMesh parse_obj(std::string_view text, const std::string& path) {
  return ObjReader(text, path).read();
}

ObjMesh load_obj(const std::string& path) {
  return parse_obj(read_text_input(path, "mesh", kMaxMeshBytes), path);
}

}  // namespace arbor::formats
