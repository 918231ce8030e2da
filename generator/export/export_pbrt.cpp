// pbrt-v4 writer.
#include "generator/export/export_pbrt.h"

#include <charconv>
#include <vector>

#include "common/atomic_file.h"
#include "generator/export/text_output.h"

namespace arbor::generator {

namespace {

void put(std::string& out, float v) {
  put_number(out, v);
  out += ' ';
}

void put_vectors(const glm::vec3* v, std::size_t count, UpAxis up, std::string& out,
                 AtomicFile& file) {
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 o = oriented(v[i], up);
    put(out, o.x);
    put(out, o.y);
    put(out, o.z);
    flush_if_large(out, file);
  }
}

// One "trianglemesh" with per-vertex normals: a trunk grid or the ramiform's collars.
void append_triangle_mesh(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                          const std::vector<std::uint32_t>& indices, UpAxis up, std::string& out,
                          AtomicFile& file) {
  out += "  Shape \"trianglemesh\" \"point3 P\" [ ";
  put_vectors(positions, count, up, out, file);
  out += "]\n    \"normal N\" [ ";
  put_vectors(normals, count, up, out, file);
  out += "]\n    \"integer indices\" [ ";
  for (std::size_t i = 0; i < indices.size(); ++i) {
    out += std::to_string(indices[i]);
    out += ' ';
    if (i % 1024 == 0) flush_if_large(out, file);
  }
  out += "]\n";
}

// Every curve segment of the given material as a pbrt Bézier cylinder.
void append_curves(const CurveSet& c, std::uint16_t material, UpAxis up, std::string& out,
                   AtomicFile& file) {
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c.segments[i].material != material) continue;
    const glm::vec4 p0 = c.points[2 * i], p1 = c.points[2 * i + 1];
    const glm::vec4 b1 = p0 + c.tangents[2 * i] / 3.0f, b2 = p1 - c.tangents[2 * i + 1] / 3.0f;
    out +=
        "  Shape \"curve\" \"string basis\" \"bezier\" \"string type\" \"cylinder\" \"point3 P\" "
        "[ ";
    for (const glm::vec4& q : {p0, b1, b2, p1}) {
      const glm::vec3 o = oriented(glm::vec3(q), up);
      put(out, o.x);
      put(out, o.y);
      put(out, o.z);
    }
    out += "] \"float width0\" ";
    put(out, 2.0f * p0.w);
    out += "\"float width1\" ";
    put(out, 2.0f * p1.w);
    out += "\n";
    flush_if_large(out, file);
  }
}

}  // namespace

void append_pbrt_shapes(const TreeGeometry& g, const std::string& bark_material,
                        const std::string& leaf_material, UpAxis up, std::string& out,
                        AtomicFile& file) {
  out += "AttributeBegin\n  " + bark_material + "\n";
  append_curves(g.curves, kMaterialBark, up, out, file);
  const GridSet& gs = g.grids;
  std::vector<std::uint32_t> indices;
  for (const DisplacedGrid& d : gs.grids) {
    indices.clear();
    for (std::uint32_t j = 0; j + 1 < d.height; ++j) {
      for (std::uint32_t i = 0; i + 1 < d.width; ++i) {
        const std::uint32_t a = j * d.width + i, b = a + 1, cc = a + d.width, e = cc + 1;
        indices.insert(indices.end(), {a, b, e, a, e, cc});
      }
    }
    const std::size_t count = static_cast<std::size_t>(d.width) * d.height;
    append_triangle_mesh(&gs.vertices[d.first_vertex], &gs.normals[d.first_vertex], count, indices,
                         up, out, file);
  }
  const RamiformSet& r = g.ramiforms;
  if (r.triangle_count() > 0) {
    append_triangle_mesh(r.positions.data(), r.normals.data(), r.positions.size(), r.indices, up,
                         out, file);
  }
  out += "AttributeEnd\n";
  const LeafMesh lm = leaf_triangles(g);
  if (lm.triangle_count() > 0) {
    out += "AttributeBegin\n  " + leaf_material + "\n";
    append_curves(g.curves, kMaterialLeafFront, up, out, file);  // the petioles
    out += "  Shape \"trianglemesh\" \"point3 P\" [ ";
    for (const glm::vec3& q : lm.positions) {
      const glm::vec3 p = oriented(q, up);
      put(out, p.x);
      put(out, p.y);
      put(out, p.z);
      flush_if_large(out, file);
    }
    out += "]\n    \"point2 uv\" [ ";
    for (const glm::vec2& t : lm.uvs) {
      put(out, t.x);
      put(out, t.y);
      flush_if_large(out, file);
    }
    out += "]\n    \"integer indices\" [ ";
    for (std::uint32_t i : lm.indices) {
      out += std::to_string(i);
      out += ' ';
      flush_if_large(out, file);
    }
    out += "]\nAttributeEnd\n";
  }
}

std::string pbrt_rgb(const char* name, const Rgb& c) {
  std::string out = std::string("\"rgb ") + name + "\" [ ";
  for (double v : c) put(out, static_cast<float>(v));
  return out + "]";
}

std::string pbrt_leaf_material(const Rgb& front, const Rgb& back, const Rgb& transmittance) {
  Rgb mean{};
  for (int i = 0; i < 3; ++i) mean[i] = 0.5 * (front[i] + back[i]);
  return "\"diffusetransmission\" " + pbrt_rgb("reflectance", mean) + " " +
         pbrt_rgb("transmittance", transmittance);
}

void write_pbrt(const TreeGeometry& g, const BarkLook& bark, const LeafLook& leaf,
                const std::string& path, UpAxis up) {
  AtomicFile file(path);
  std::string out =
      std::string(
          "# arbor tree for pbrt-v4: Include this file inside the world block.\n"
          "# Units are metres, ") +
      (up == UpAxis::Y ? "y" : "z") +
      " is up. Limbs are exact cubic curves; pbrt's diffusetransmission\n"
      "# has one reflectance for both faces: the mean of the leaf's front and back reflectance.\n";
  append_pbrt_shapes(
      g, "Material \"diffuse\" " + pbrt_rgb("reflectance", bark.albedo),
      "Material " + pbrt_leaf_material(leaf.reflectance, leaf.back_reflectance, leaf.transmittance),
      up, out, file);
  file.write(out);
  file.commit();
}

}  // namespace arbor::generator
