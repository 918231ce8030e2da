// pbrt-v4 writer.
#include "generator/export/export_pbrt.h"

#include <charconv>

#include "common/atomic_file.h"
#include "generator/export/text_output.h"

namespace arbor::gen {

namespace {

void put(std::string& out, float v) {
  put_number(out, v);
  out += ' ';
}

void put_rgb(std::string& out, const char* name, const Rgb& c) {
  out += std::string("\"rgb ") + name + "\" [ ";
  for (double v : c) put(out, static_cast<float>(v));
  out += "] ";
}

}  // namespace

void write_pbrt(const TreeGeometry& g, const BarkLook& bark, const LeafLook& leaf,
                const std::string& path) {
  AtomicFile file(path);
  std::string out =
      "# arbor tree for pbrt-v4: Include this file inside the world block.\n"
      "# Units are metres, z is up. Limbs are exact cubic curves; pbrt's diffusetransmission\n"
      "# has one reflectance, so the leaves' lighter back side uses the front reflectance.\n";
  out += "AttributeBegin\n  Material \"diffuse\" ";
  put_rgb(out, "reflectance", bark.albedo);
  out += "\n";
  const CurveSet& c = g.curves;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const glm::vec4 p0 = c.points[2 * i], p1 = c.points[2 * i + 1];
    const glm::vec4 b1 = p0 + c.tangents[2 * i] / 3.0f, b2 = p1 - c.tangents[2 * i + 1] / 3.0f;
    out += "  Shape \"curve\" \"string basis\" \"bezier\" \"string type\" \"cylinder\" \"point3 P\" [ ";
    for (const glm::vec4& q : {p0, b1, b2, p1}) {
      put(out, q.x);
      put(out, q.y);
      put(out, q.z);
    }
    out += "] \"float width0\" ";
    put(out, 2.0f * p0.w);
    out += "\"float width1\" ";
    put(out, 2.0f * p1.w);
    out += "\n";
    flush_if_large(out, file);
  }
  const GridSet& gs = g.grids;
  for (const DisplacedGrid& d : gs.grids) {
    out += "  Shape \"trianglemesh\" \"point3 P\" [ ";
    const std::size_t count = static_cast<std::size_t>(d.width) * d.height;
    for (std::size_t v = 0; v < count; ++v) {
      const glm::vec3 p = gs.vertices[d.first_vertex + v];
      put(out, p.x); put(out, p.y); put(out, p.z);
      flush_if_large(out, file);
    }
    out += "]\n    \"normal N\" [ ";
    for (std::size_t v = 0; v < count; ++v) {
      const glm::vec3 n = gs.normals[d.first_vertex + v];
      put(out, n.x); put(out, n.y); put(out, n.z);
      flush_if_large(out, file);
    }
    out += "]\n    \"integer indices\" [ ";
    for (std::uint32_t j = 0; j + 1 < d.height; ++j) {
      for (std::uint32_t i = 0; i + 1 < d.width; ++i) {
        const std::uint32_t a = j * d.width + i, b = a + 1, cc = a + d.width, e = cc + 1;
        for (std::uint32_t k : {a, b, e, a, e, cc}) out += std::to_string(k) + ' ';
      }
      flush_if_large(out, file);
    }
    out += "]\n";
  }
  out += "AttributeEnd\n";
  const LeafMesh lm = leaf_triangles(g);
  if (lm.triangle_count() > 0) {
    out += "AttributeBegin\n  Material \"diffusetransmission\" ";
    put_rgb(out, "reflectance", leaf.reflectance);
    put_rgb(out, "transmittance", leaf.transmittance);
    out += "\n  Shape \"trianglemesh\" \"point3 P\" [ ";
    for (const glm::vec3& p : lm.positions) {
      put(out, p.x); put(out, p.y); put(out, p.z);
      flush_if_large(out, file);
    }
    out += "]\n    \"point2 uv\" [ ";
    for (const glm::vec2& t : lm.uvs) {
      put(out, t.x); put(out, t.y);
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
  file.write(out);
  file.commit();
}

}  // namespace arbor::gen
