// OBJ (+ MTL) and PLY writers for TreeMesh; every file is written atomically.
#include "generator/export/export_mesh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>

#include "common/atomic_file.h"
#include "common/strings.h"

namespace arbor::generator {

namespace {

constexpr int kPositionDecimals = 5;  // 10 µm
constexpr int kUnitDecimals = 4;      // normals and uv

int digits(std::uint32_t v) {
  int n = 1;
  for (; v >= 10; v /= 10) ++n;
  return n;
}

void put_rgb(std::string& out, const char* key, const Rgb& c) {
  out += key;
  for (double v : c) {
    out += ' ';
    put_fixed(out, static_cast<float>(v), 4);
  }
  out += '\n';
}

// The .mtl: bark as a Lambertian colour; the leaf's front reflectance as Kd, its transmittance as
// Tf, its cuticle as an untinted specular (Ks = the coat's reflectance at normal incidence,
// ((n - 1)/(n + 1))², Ns the Blinn–Phong exponent 2/α² - 2 of GGX α = roughness², and the PBR
// extension Pr = roughness that Blender's importer reads). MTL has no back side: the back
// reflectance is stated in a comment.
std::string mtl_text(const MeshLooks& looks, const std::string& obj_name) {
  std::string out = "# arbor materials for " + obj_name + " (" + looks.species +
                    "): colours are scene-linear RGB, as in the species file\n";
  out += "newmtl bark\n";
  put_rgb(out, "Kd", looks.bark.albedo);
  out += "Ks 0 0 0\nillum 1\n\n";
  const LeafLook& l = looks.leaf;
  out += "# leaf back reflectance (MTL has one side):";
  for (double v : l.back_reflectance) {
    out += ' ';
    put_fixed(out, static_cast<float>(v), 4);
  }
  out += "\nnewmtl leaf\n";
  put_rgb(out, "Kd", l.reflectance);
  put_rgb(out, "Tf", l.transmittance);
  const double f0 =
      l.cuticle_ior > 1.0 ? std::pow((l.cuticle_ior - 1.0) / (l.cuticle_ior + 1.0), 2.0) : 0.0;
  put_rgb(out, "Ks", {f0, f0, f0});
  if (f0 > 0.0) {
    const double alpha = std::max(l.cuticle_roughness * l.cuticle_roughness, 1e-3);
    out += "Ns ";
    put_fixed(out, static_cast<float>(std::min(2.0 / (alpha * alpha) - 2.0, 1000.0)), 1);
    out += "\nPr ";
    put_fixed(out, static_cast<float>(l.cuticle_roughness), 4);
    out += '\n';
  }
  out += f0 > 0.0 ? "illum 2\n" : "illum 1\n";
  return out;
}

}  // namespace

std::string mtl_path_for(const std::string& obj_path) {
  return (ends_with(obj_path, ".obj") ? obj_path.substr(0, obj_path.size() - 4) : obj_path) +
         ".mtl";
}

void write_obj(const TreeMesh& mesh, const std::string& path, const MeshLooks& looks, UpAxis up) {
  const std::string mtl = mtl_path_for(path);
  AtomicFile file(path);
  AtomicFile mtl_file(mtl);
  mtl_file.write(mtl_text(looks, file_name(path)));
  std::string out = "# arbor tree mesh (" + looks.species +
                    "): groups and materials bark and leaf, " + (up == UpAxis::Y ? "y" : "z") +
                    " up, metres\nmtllib " + file_name(mtl) + "\no tree\n";
  // Vertices are written just before the first face that uses them, and each corner names its
  // vertex by the shorter of its absolute index and its (negative) distance back from the last
  // vertex written: tessellated rings refer to their neighbours, so most corners take 2–3 digits.
  std::size_t written = 0;
  const auto write_vertices_to = [&](std::size_t end) {
    for (; written < end; ++written) {
      const glm::vec3 p = oriented(mesh.positions[written], up);
      const glm::vec3 n = oriented(mesh.normals[written], up);
      const glm::vec2& t = mesh.uvs[written];
      out += "v ";
      put_fixed(out, p.x, kPositionDecimals);
      out += ' ';
      put_fixed(out, p.y, kPositionDecimals);
      out += ' ';
      put_fixed(out, p.z, kPositionDecimals);
      out += "\nvt ";
      put_fixed(out, t.x, kUnitDecimals);
      out += ' ';
      put_fixed(out, t.y, kUnitDecimals);
      out += "\nvn ";
      put_fixed(out, n.x, kUnitDecimals);
      out += ' ';
      put_fixed(out, n.y, kUnitDecimals);
      out += ' ';
      put_fixed(out, n.z, kUnitDecimals);
      out += '\n';
      flush_if_large(out, file);
    }
  };
  for (size_t tri = 0; tri < mesh.triangle_count(); ++tri) {
    const std::uint32_t* corner = &mesh.indices[tri * 3];
    write_vertices_to(std::size_t{std::max({corner[0], corner[1], corner[2]})} + 1);
    if (tri == 0) out += "g bark\nusemtl bark\n";
    if (tri == mesh.bark_triangles) out += "g leaf\nusemtl leaf\n";
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t absolute = corner[k] + 1,
                          back = static_cast<std::uint32_t>(written - corner[k]);
      const bool relative = digits(back) + 1 < digits(absolute);  // "-back" is shorter
      char index[16];
      index[0] = '-';
      const char* end =
          std::to_chars(index + 1, index + sizeof index, relative ? back : absolute).ptr;
      const std::string_view text(relative ? index : index + 1,
                                  static_cast<std::size_t>(end - (relative ? index : index + 1)));
      out += ' ';
      out += text;
      out += '/';
      out += text;
      out += '/';
      out += text;
    }
    out += '\n';
    flush_if_large(out, file);
  }
  write_vertices_to(mesh.positions.size());  // any that no triangle uses
  file.write(out);
  mtl_file.commit();
  file.commit();
}

void write_ply(const TreeMesh& mesh, const std::string& path, const MeshLooks& looks, UpAxis up) {
  AtomicFile file(path, true);
  std::string colours;
  put_rgb(colours, "comment material 0 bark albedo", looks.bark.albedo);
  put_rgb(colours, "comment material 1 leaf reflectance", looks.leaf.reflectance);
  put_rgb(colours, "comment material 1 leaf back reflectance", looks.leaf.back_reflectance);
  put_rgb(colours, "comment material 1 leaf transmittance", looks.leaf.transmittance);
  std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment arbor tree mesh (" + looks.species + "), " +
      (up == UpAxis::Y ? "y" : "z") + " up, metres: material 0 bark, 1 leaf\n" + colours +
      "element vertex " + std::to_string(mesh.positions.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property float s\nproperty float t\n"
      "element face " +
      std::to_string(mesh.triangle_count()) +
      "\nproperty list uchar int vertex_indices\nproperty uchar material\nend_header\n";
  file.write(header);
  static_assert(sizeof(float) == 4, "PLY floats are 32-bit");
  std::string out;
  out.reserve(1u << 21);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = oriented(mesh.positions[i], up);
    const glm::vec3 n = oriented(mesh.normals[i], up);
    const float v[8] = {p.x, p.y, p.z, n.x, n.y, n.z, mesh.uvs[i].x, mesh.uvs[i].y};
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

}  // namespace arbor::generator
