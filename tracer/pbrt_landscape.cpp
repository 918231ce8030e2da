// A landscape's parts in the pbrt-v4 export: what pbrt-v4 cannot compute (the terrain's cover,
// the rock's pattern) is baked or averaged here, as docs/rendering.md says.
#include "tracer/pbrt_landscape.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/atomic_file.h"
#include "common/strings.h"
#include "generator/export/text_output.h"

namespace arbor::tracer {

namespace {

constexpr int kMostTexels = 4096;  // along the longer side of the terrain's albedo

std::string stem_of(const std::string& pbrt_path) {
  return ends_with(pbrt_path, ".pbrt") ? pbrt_path.substr(0, pbrt_path.size() - 5) : pbrt_path;
}

// Little-endian bytes, whatever the machine's order.
void put_u32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
}
void put_float(std::string& out, float f) {
  std::uint32_t v;
  std::memcpy(&v, &f, sizeof v);
  put_u32(out, v);
}

std::string number(float v) {
  std::string s;
  generator::put_number(s, v);
  return s;
}

}  // namespace

std::string terrain_mesh_path_for(const std::string& pbrt_path) {
  return stem_of(pbrt_path) + ".terrain.ply";
}
std::string terrain_albedo_path_for(const std::string& pbrt_path) {
  return stem_of(pbrt_path) + ".terrain.exr";
}
std::string surround_mesh_path_for(const std::string& pbrt_path) {
  return stem_of(pbrt_path) + ".surround.ply";
}
std::string surround_albedo_path_for(const std::string& pbrt_path) {
  return stem_of(pbrt_path) + ".surround.exr";
}

void write_terrain_ply(const scene::Terrain& t, const std::string& path) {
  const int nx = t.columns(), ny = t.rows();
  const std::size_t vertices = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  const std::size_t faces = 2 * static_cast<std::size_t>(nx - 1) * static_cast<std::size_t>(ny - 1);
  AtomicFile file(path, true);
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment arbor terrain: "
      "z up, metres; uv over the square\nelement vertex " +
      std::to_string(vertices) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float "
      "ny\nproperty float nz\nproperty float u\nproperty float v\nelement face " +
      std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const glm::dvec2 o = t.origin(), e = t.extent();
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const glm::vec3 p = t.vertices()[static_cast<std::size_t>(j) * nx + i];
      const glm::vec3 n = t.normal(p.x, p.y);
      for (float f : {p.x, p.y, p.z, n.x, n.y, n.z}) put_float(out, f);
      put_float(out, static_cast<float>((p.x - o.x) / e.x));
      put_float(out, static_cast<float>((p.y - o.y) / e.y));
    }
    if (out.size() > (1u << 22)) {
      file.write(out);
      out.clear();
    }
  }
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const auto v0 = static_cast<std::uint32_t>(j * nx + i), v1 = v0 + 1,
                 v3 = v0 + static_cast<std::uint32_t>(nx), v2 = v3 + 1;
      const std::uint32_t corners[6] = {v0, v1, v3, v2, v3, v1};
      for (int k = 0; k < 6; ++k) {
        if (k % 3 == 0) out.push_back(3);
        put_u32(out, corners[k]);
      }
    }
    if (out.size() > (1u << 22)) {
      file.write(out);
      out.clear();
    }
  }
  file.write(out);
  file.commit();
}

TerrainTexels terrain_texels(const scene::Terrain& t) {
  const glm::dvec2 e = t.extent();
  const double texel = std::max(0.5 * t.spacing(), std::max(e.x, e.y) / kMostTexels);
  return {std::max(1, static_cast<int>(std::lround(e.x / texel))),
          std::max(1, static_cast<int>(std::lround(e.y / texel)))};
}

imaging::Image terrain_albedo(const scene::Terrain& t, const materials::GroundMaterial& ground,
                              const imaging::ColorTransform& to_pbrt, std::size_t& clamped) {
  const TerrainTexels n = terrain_texels(t);
  imaging::Image img;
  img.width = img.full_width = n.columns;
  img.height = img.full_height = n.rows;
  img.beauty.resize(static_cast<std::size_t>(n.columns) * static_cast<std::size_t>(n.rows));
  img.alpha.assign(img.beauty.size(), 1.0f);
  const glm::dvec2 o = t.origin(), e = t.extent();
  const double dx = e.x / n.columns, dy = e.y / n.rows;
  std::atomic<std::size_t> pushed{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, n.rows), [&](const tbb::blocked_range<int>& rows) {
    std::size_t local = 0;
    for (int row = rows.begin(); row != rows.end(); ++row) {
      for (int column = 0; column < n.columns; ++column) {
        glm::vec3 sum(0.0f);
        for (int s = 0; s < 4; ++s) {
          materials::SurfacePoint p;
          const double x = o.x + (column + 0.25 + 0.5 * (s & 1)) * dx;
          const double y = o.y + e.y - (row + 0.25 + 0.5 * (s >> 1)) * dy;
          p.ground = glm::vec2(static_cast<float>(x), static_cast<float>(y));
          p.terrain = t.cover(x, y);
          sum += ground.albedo_at(p);
        }
        float rgb[3] = {sum.x / 4.0f, sum.y / 4.0f, sum.z / 4.0f};
        if (to_pbrt) to_pbrt(rgb);
        const glm::vec3 v(rgb[0], rgb[1], rgb[2]);
        const glm::vec3 kept = glm::clamp(v, glm::vec3(0.0f), glm::vec3(1.0f));
        local += kept != v;
        img.beauty[static_cast<std::size_t>(row) * n.columns + column] = kept;
      }
    }
    pushed += local;
  });
  clamped = pushed;
  return img;
}

glm::vec3 mean_rock_albedo(const materials::GroundMaterial& rock) {
  // 200 × 200 points 0.2 m apart: many of the pattern's 2 m and 0.6 m features.
  glm::dvec3 sum(0.0);
  for (int j = 0; j < 200; ++j) {
    for (int i = 0; i < 200; ++i)
      sum += glm::dvec3(rock.rock_at(glm::vec2(0.2f * i + 0.1f, 0.2f * j + 0.1f)));
  }
  return glm::vec3(sum / 40000.0);
}

std::string rocks_text(const scene::Rocks& rocks, const std::string& material) {
  std::string out;
  for (std::size_t s = 0; s < rocks.shapes.size(); ++s) {
    const scene::RockShape& shape = rocks.shapes[s];
    out += "ObjectBegin \"rock" + std::to_string(s + 1) + "\"\n  NamedMaterial \"" + material +
           "\"\n  Shape \"trianglemesh\" \"point3 P\" [ ";
    for (const glm::vec3& p : shape.positions)
      out += number(p.x) + " " + number(p.y) + " " + number(p.z) + " ";
    out += "]\n    \"normal N\" [ ";
    for (const glm::vec3& n : shape.normals)
      out += number(n.x) + " " + number(n.y) + " " + number(n.z) + " ";
    out += "]\n    \"integer indices\" [ ";
    for (std::uint32_t i : shape.indices) out += std::to_string(i) + " ";
    out += "]\nObjectEnd\n";
  }
  for (const scene::RockPlacement& p : rocks.placements) {
    // pbrt's Transform takes the matrix column by column, as glm stores it.
    out += "AttributeBegin\n  Transform [ ";
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) out += number(p.to_world[c][r]) + " ";
    }
    out += "]\n  ObjectInstance \"rock" + std::to_string(p.shape + 1) + "\"\nAttributeEnd\n";
  }
  return out;
}

}  // namespace arbor::tracer
