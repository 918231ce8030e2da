// OBJ and PLY writers for TreeMesh; both write atomically.
#include <charconv>
#include <cstring>
#include <string>

#include "common/atomic_file.h"
#include "generator/export/text_output.h"
#include "generator/export/export_mesh.h"

namespace arbor::gen {

namespace {

void put(std::string& out, float v) { put_number(out, v); }
void put(std::string& out, std::uint32_t v) {
  char buf[16];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace

void write_obj(const TreeMesh& mesh, const std::string& path) {
  AtomicFile file(path);
  std::string out = "# arbor tree mesh: groups bark and leaf\no tree\n";
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    const glm::vec3& n = mesh.normals[i];
    const glm::vec2& t = mesh.uvs[i];
    out += "v "; put(out, p.x); out += ' '; put(out, p.y); out += ' '; put(out, p.z);
    out += "\nvt "; put(out, t.x); out += ' '; put(out, t.y);
    out += "\nvn "; put(out, n.x); out += ' '; put(out, n.y); out += ' '; put(out, n.z);
    out += '\n';
    flush_if_large(out, file);
  }
  for (size_t tri = 0; tri < mesh.triangle_count(); ++tri) {
    if (tri == 0) out += "g bark\n";
    if (tri == mesh.bark_triangles) out += "g leaf\n";
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[tri * 3 + static_cast<size_t>(k)] + 1;
      out += ' '; put(out, v); out += '/'; put(out, v); out += '/'; put(out, v);
    }
    out += '\n';
    flush_if_large(out, file);
  }
  file.write(out);
  file.commit();
}

void write_ply(const TreeMesh& mesh, const std::string& path) {
  AtomicFile file(path, true);
  std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment arbor tree mesh: material 0 bark, 1 leaf\n"
      "element vertex " + std::to_string(mesh.positions.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property float s\nproperty float t\n"
      "element face " + std::to_string(mesh.triangle_count()) +
      "\nproperty list uchar int vertex_indices\nproperty uchar material\nend_header\n";
  file.write(header);
  static_assert(sizeof(float) == 4, "PLY floats are 32-bit");
  std::string out;
  out.reserve(1u << 21);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const float v[8] = {mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z,
                        mesh.normals[i].x,   mesh.normals[i].y,   mesh.normals[i].z,
                        mesh.uvs[i].x,       mesh.uvs[i].y};
    out.append(reinterpret_cast<const char*>(v), sizeof v);  // x86-64 and arm64 are little-endian
    flush_if_large(out, file);
  }
  for (size_t tri = 0; tri < mesh.triangle_count(); ++tri) {
    char face[1 + 12 + 1];
    face[0] = 3;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::int32_t>(mesh.indices[tri * 3 + static_cast<size_t>(k)]);
      std::memcpy(face + 1 + 4 * k, &v, 4);
    }
    face[13] = tri < mesh.bark_triangles ? 0 : 1;
    out.append(face, sizeof face);
    flush_if_large(out, file);
  }
  file.write(out);
  file.commit();
}

}  // namespace arbor::gen
