// The scene as pbrt-v4 sees it. What pbrt-v4 cannot state is said in the file's
// opening comment and in docs/rendering.md.
#include "tracer/pbrt_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/strings.h"
#include "generator/export/export_pbrt.h"
#include "generator/export/text_output.h"
#include "imaging/color.h"
#include "imaging/image_output.h"
#include "scene/scene.h"
#include "tracer/lights/sky.h"
#include "tracer/pbrt_landscape.h"

namespace arbor::tracer {

namespace {

constexpr float kPi = 3.14159265358979323846f;

const PbrtColorSpace kPbrtSpaces[] = {
    {"srgb", {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}},
    {"rec2020", {0.708f, 0.292f, 0.170f, 0.797f, 0.131f, 0.046f, 0.3127f, 0.3290f}},
    {"aces2065-1", {0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f}},
    {"dci-p3", {0.680f, 0.320f, 0.265f, 0.690f, 0.150f, 0.060f, 0.3127f, 0.3290f}},
};

std::string number(double v) {
  std::string s;
  generator::put_number(s, static_cast<float>(v));
  return s;
}

std::string triple(const glm::vec3& v) {
  return number(v.x) + " " + number(v.y) + " " + number(v.z);
}

// Colours in pbrt's space; reflectances must lie in [0, 1] there (pbrt-v4 refuses others), so a
// component pushed past by the change of primaries is clamped and reported.
struct Colors {
  imaging::ColorTransform to_pbrt;  // empty: the same space
  std::vector<std::string>* clamped = nullptr;

  glm::vec3 light(const glm::vec3& c) const {
    float rgb[3] = {c.x, c.y, c.z};
    if (to_pbrt) to_pbrt(rgb);
    return glm::max(glm::vec3(rgb[0], rgb[1], rgb[2]), glm::vec3(0.0f));
  }
  glm::vec3 reflectance(const glm::vec3& c, const std::string& what) const {
    float rgb[3] = {c.x, c.y, c.z};
    if (to_pbrt) to_pbrt(rgb);
    const glm::vec3 v(rgb[0], rgb[1], rgb[2]);
    const glm::vec3 kept = glm::clamp(v, glm::vec3(0.0f), glm::vec3(1.0f));
    if (kept != v && clamped)
      clamped->push_back(what + " (" + triple(v) + " → " + triple(kept) + ")");
    return kept;
  }
  std::string rgb(const char* name, const glm::vec3& c, const std::string& what) const {
    return generator::pbrt_rgb(name, to_rgb(reflectance(c, what)));
  }
  static Rgb to_rgb(const glm::vec3& c) { return {c.x, c.y, c.z}; }
};

// A material statement's body, by what it is made of: one MakeNamedMaterial per distinct body.
class Materials {
 public:
  explicit Materials(const Colors& colors) : colors_(colors) {}

  // The pbrt statement of each material kind (a new kind must add one: std::visit needs it).
  std::string statement(const materials::LeafMaterial& l, const std::string& label) const {
    return generator::pbrt_leaf_material(
        Colors::to_rgb(colors_.reflectance(l.front, label + " front")),
        Colors::to_rgb(colors_.reflectance(l.back, label + " back")),
        Colors::to_rgb(colors_.reflectance(l.transmittance, label + " transmittance")));
  }
  std::string statement(const materials::BarkMaterial& b, const std::string& label) const {
    return "\"diffuse\" " + colors_.rgb("reflectance", b.albedo, label);
  }
  std::string statement(const materials::GroundMaterial& g, const std::string& label) const {
    // The patches' noise has no pbrt counterpart: their cover-weighted mean, for the ground
    // beyond the baked square around the camera (write_ground_exr).
    const float c = g.cover;
    return "\"diffuse\" " +
           colors_.rgb("reflectance", (1.0f - c) * g.albedo + c * g.patch_albedo, label);
  }
  std::string statement(const materials::DiffuseMaterial& d, const std::string& label) const {
    return "\"diffuse\" " + colors_.rgb("reflectance", d.albedo, label);
  }

  // The name of the material for `m` (in scene space), made on first use.
  std::string name_of(const materials::Material& m, const std::string& label) {
    const std::string body = std::visit([&](const auto& k) { return statement(k, label); }, m.kind);
    auto [at, fresh] = names_.emplace(body, "");
    if (fresh) {
      at->second = "m" + std::to_string(names_.size()) + " " + label;
      text_ += "MakeNamedMaterial \"" + at->second + "\" \"string type\" " + body + "\n";
    }
    return at->second;
  }
  const std::string& text() const { return text_; }

 private:
  const Colors& colors_;
  std::map<std::string, std::string> names_;  // body → name
  std::string text_;
};

std::string transform_of(const glm::mat4& m) {
  // pbrt's Transform takes the matrix column by column, as glm stores it.
  const float* f = glm::value_ptr(m);
  std::string s = "Transform [ ";
  for (int i = 0; i < 16; ++i) s += number(f[i]) + " ";
  return s + "]";
}

// The sky as pbrt-v4's equal-area square. With `fill_below` (the scene has a ground, which the
// export writes 10 km each way), texels below the horizon take the horizon's radiance at their
// azimuth instead of black: the ground hides them, and pbrt's bilinear lookup of the texels just
// above the horizon then blends no black into them (at 512 texels a side the last rows rendered
// 0.31-0.67x dark).
void write_sky_exr(const Sky& sky, const Colors& colors, const PbrtColorSpace& space, int n,
                   bool fill_below, const std::string& path) {
  imaging::Image img;
  img.width = img.full_width = n;
  img.height = img.full_height = n;
  const std::size_t count = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  img.beauty.resize(count);
  img.alpha.assign(count, 1.0f);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      glm::vec3 d = glm::normalize(equal_area_square_to_sphere(
          glm::vec2((static_cast<float>(x) + 0.5f) / static_cast<float>(n),
                    (static_cast<float>(y) + 0.5f) / static_cast<float>(n))));
      // The texels centred on the horizon itself (z = 0 exactly: the square's diamond runs through
      // texel centres) belong to the sky above it; arbor's map puts z = 0 in its first row below,
      // which is black, and pbrt's bilinear lookup spread that black over the last half degree of
      // sky (0.02-0.2x in pbrt at 512 texels).
      if ((fill_below && d.z < 0.0f) || d.z == 0.0f) {
        const float across = std::hypot(d.x, d.y);
        d = across > 1e-6f ? glm::normalize(glm::vec3(d.x / across, d.y / across, 1e-4f))
                           : glm::vec3(1.0f, 0.0f, 1e-4f);
      }
      img.beauty[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) +
                 static_cast<std::size_t>(x)] = colors.light(sky.radiance(d));
    }
  }
  imaging::OutputSpec output;
  // Linear radiance in pbrt's colour space `space` (its chromaticities say which): OIIO's name for
  // linear, not pbrt's "srgb", which OIIO reads as the sRGB curve (oiiotool darkened it 5x).
  output.colorspace = "Linear";
  output.pixel_type = imaging::PixelType::Float;
  imaging::ExrMetadata meta;
  meta.scene = "arbor sky for pbrt-v4 (equal-area octahedral map), linear in pbrt's colour space " +
               std::string(space.name) +
               (fill_below ? "; below the horizon, the horizon's radiance" : "");
  meta.chromaticities = space.chromaticities;
  meta.render_attributes = false;
  imaging::write_exr(img, output, meta, path);
}

}  // namespace

glm::vec3 equal_area_square_to_sphere(glm::vec2 uv) {
  const float u = 2.0f * uv.x - 1.0f, v = 2.0f * uv.y - 1.0f;
  const float up = std::fabs(u), vp = std::fabs(v);
  const float signed_distance = 1.0f - (up + vp);
  const float r = 1.0f - std::fabs(signed_distance);
  const float phi = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * kPi / 4.0f;
  const float z = std::copysign(1.0f - r * r, signed_distance);
  const float cos_phi = std::copysign(std::cos(phi), u), sin_phi = std::copysign(std::sin(phi), v);
  const float s = r * std::sqrt(std::max(0.0f, 2.0f - r * r));
  return glm::vec3(cos_phi * s, sin_phi * s, z);
}

PbrtColorSpace pbrt_color_space_for(const std::vector<float>& c) {
  for (const PbrtColorSpace& p : kPbrtSpaces) {
    bool same = c.size() == 8;
    for (std::size_t i = 0; same && i < 8; ++i)
      same = std::fabs(c[i] - p.chromaticities[i]) < 1e-3f;
    if (same) return p;
  }
  return kPbrtSpaces[2];
}

std::string sky_path_for(const std::string& pbrt_path) {
  return (ends_with(pbrt_path, ".pbrt") ? pbrt_path.substr(0, pbrt_path.size() - 5) : pbrt_path) +
         ".sky.exr";
}

std::string ground_path_for(const std::string& pbrt_path) {
  return (ends_with(pbrt_path, ".pbrt") ? pbrt_path.substr(0, pbrt_path.size() - 5) : pbrt_path) +
         ".ground.exr";
}

namespace {

// The ground's patches have no pbrt counterpart (arbor's noise): near the camera they are baked
// into an image, kGroundTexels a side over kGroundHalf metres each way (0.25 m a texel, a dozen
// or more across a patch); the rest of the 10 km ground takes their cover-weighted mean.
constexpr int kGroundTexels = 1024;
constexpr float kGroundHalf = 128.0f;

// The ground's albedo over the square centred at `centre`, in pbrt's colour space, as pbrt's
// imagemap reads it: row 0 at the square's +y edge (pbrt flips v: texture (0,0) is the image's
// lower left), column 0 at its −x edge.
void write_ground_exr(const materials::GroundMaterial& ground, const Colors& colors,
                      const PbrtColorSpace& space, glm::vec2 centre, const std::string& path) {
  imaging::Image img;
  img.width = img.full_width = img.height = img.full_height = kGroundTexels;
  img.beauty.resize(static_cast<std::size_t>(kGroundTexels) * kGroundTexels);
  img.alpha.assign(img.beauty.size(), 1.0f);
  const float texel = 2.0f * kGroundHalf / kGroundTexels;
  for (int row = 0; row < kGroundTexels; ++row) {
    for (int column = 0; column < kGroundTexels; ++column) {
      const glm::vec2 xy(centre.x - kGroundHalf + (column + 0.5f) * texel,
                         centre.y + kGroundHalf - (row + 0.5f) * texel);
      const float w = ground.patch(xy);
      img.beauty[static_cast<std::size_t>(row) * kGroundTexels + column] = colors.reflectance(
          ground.albedo + (ground.patch_albedo - ground.albedo) * w, "the ground's patches");
    }
  }
  imaging::OutputSpec output;
  output.colorspace = "Linear";
  output.pixel_type = imaging::PixelType::Half;
  imaging::ExrMetadata meta;
  meta.scene = "arbor ground albedo for pbrt-v4 (its patches), linear in pbrt's colour space " +
               std::string(space.name);
  meta.chromaticities = space.chromaticities;
  meta.render_attributes = false;
  imaging::write_exr(img, output, meta, path);
}

// The opening comment, colour space, camera, film, sampler and integrator, up to WorldBegin.
std::string camera_text(const scene::RenderInput& input, const PbrtColorSpace& space,
                        bool converted, const std::string& out) {
  const spec::RenderSettings& r = input.render;
  std::string text = "# pbrt-v4 scene written by arbor from " + input.scene + "\n";
  text +=
      "# Units are metres, z is up; colours are in pbrt's \"" + std::string(space.name) +
      "\" space (arbor's scene_linear" + (converted ? ", converted" : "") +
      ").\n"
      "# Not in pbrt-v4, so not here: the sun's disk (a distant light is a point), the leaves'\n"
      "# two sides (one reflectance, the mean of front and back) and their cuticle, bark\n"
      "# roughness (Oren-Nayar) and relief, albedo maps, the ground's patches beyond 128 m of the\n"
      "# camera (their mean albedo there; nearer, an image), the [meadow]'s grass blades, the\n"
      "# terrain's cover and the rocks' lichen as arbor computes them (the terrain's albedo is\n"
      "# baked into an image, the rocks' is their mean), the transparent sky, the AOVs, arbor's\n"
      "# sampling (pbrt samples its own way).\n";
  text += "ColorSpace \"" + std::string(space.name) + "\"\n";
  // pbrt's camera space is left-handed: mirroring x keeps arbor's right-handed image unmirrored.
  const spec::CameraDesc& cam = input.camera;
  text += "Scale -1 1 1\nLookAt " + number(cam.position[0]) + " " + number(cam.position[1]) + " " +
          number(cam.position[2]) + "  " + number(cam.look_at[0]) + " " + number(cam.look_at[1]) +
          " " + number(cam.look_at[2]) + "  " + number(cam.up[0]) + " " + number(cam.up[1]) + " " +
          number(cam.up[2]) + "\n";
  // arbor's fov is vertical; pbrt's spans the image's shorter side.
  const double aspect = static_cast<double>(r.width) / r.height;
  const double fov = aspect >= 1.0
                         ? cam.fov
                         : 2.0 * std::atan(std::tan(cam.fov * kPi / 360.0) * aspect) * 180.0 / kPi;
  const double focus = cam.focus_distance > 0.0
                           ? cam.focus_distance
                           : std::sqrt(std::pow(cam.look_at[0] - cam.position[0], 2) +
                                       std::pow(cam.look_at[1] - cam.position[1], 2) +
                                       std::pow(cam.look_at[2] - cam.position[2], 2));
  text += "Camera \"perspective\" \"float fov\" " + number(fov);
  if (cam.aperture_radius > 0.0) {
    text += " \"float lensradius\" " + number(cam.aperture_radius) + " \"float focaldistance\" " +
            number(focus);
  }
  text += "\nFilm \"rgb\" \"integer xresolution\" " + std::to_string(r.width) +
          " \"integer yresolution\" " + std::to_string(r.height) + " \"string filename\" \"" +
          file_name(out.substr(0, out.size() - 5)) + ".exr\"\n";
  text += "PixelFilter \"triangle\" \"float xradius\" 1 \"float yradius\" 1\n";
  text += "Sampler \"zsobol\" \"integer pixelsamples\" " + std::to_string(r.spp) + "\n";
  text += "Integrator \"volpath\" \"integer maxdepth\" " + std::to_string(r.max_depth) + "\n";
  return text + "\nWorldBegin\n\n";
}

// The sun and the sky; the camera's exposure scales them (pbrt's film has no exposure of its own).
std::string lights_text(const scene::RenderInput& input, const Sky& sky, const Colors& colors,
                        const std::string& sky_path) {
  const float exposure = std::exp2(static_cast<float>(input.camera.exposure));
  std::string text;
  if (sky.has_sun() && sky.sun_irradiance() > 0.0f) {
    const glm::vec3 e = colors.light(sky.sun_irradiance_color());
    text +=
        "# the sun: irradiance on a plane facing it\nLightSource \"distant\" \"point3 from\" [ " +
        triple(sky.sun_direction()) + " ] \"point3 to\" [ 0 0 0 ] " +
        generator::pbrt_rgb("L", Colors::to_rgb(e)) + " \"float scale\" " + number(exposure) + "\n";
  }
  if (!sky.empty()) {
    text +=
        "# the sky (" + std::string(name_of(input.sky.model)) +
        "), sampled into an equal-area square\nLightSource \"infinite\" \"string filename\" \"" +
        file_name(sky_path) + "\" \"float scale\" " + number(exposure) + "\n";
  }
  return text;
}

// The trees as object instances: one object per prototype and its pair of materials (named in
// `materials` on first use), and the instances of them.
struct TreeObjects {
  std::map<std::tuple<int, std::string, std::string>, std::string>
      objects;  // (prototype, bark, leaf) → name
  std::string instances;
};

TreeObjects tree_objects(const scene::Scene& built, Materials& materials) {
  TreeObjects trees;
  for (const scene::TreeInstance& inst : built.instances) {
    const std::string label = built.object_names.at(inst.object_id - 1);
    const std::string species = label.substr(0, label.rfind('.'));
    const std::string bark = materials.name_of(inst.bark, species + " bark");
    const std::string leaf = materials.name_of(inst.leaf, species + " leaf");
    auto [at, fresh] = trees.objects.emplace(std::make_tuple(inst.prototype, bark, leaf), "");
    if (fresh) at->second = "tree" + std::to_string(trees.objects.size()) + " " + species;
    trees.instances += "AttributeBegin # " + label + "\n  " + transform_of(inst.to_world) +
                       "\n  ObjectInstance \"" + at->second + "\"\nAttributeEnd\n";
  }
  return trees;
}

// The objects' shapes, then the instances, appended to `out` (flushed to `file` as it grows).
void write_trees(const scene::Scene& built, const TreeObjects& trees, std::string& out,
                 AtomicFile& file) {
  for (const auto& [key, name] : trees.objects) {
    const generator::TreeGeometry& g =
        *built.prototypes.at(static_cast<std::size_t>(std::get<0>(key))).geometry;
    out += "ObjectBegin \"" + name + "\"\n";
    generator::append_pbrt_shapes(g, "NamedMaterial \"" + std::get<1>(key) + "\"",
                                  "NamedMaterial \"" + std::get<2>(key) + "\"",
                                  generator::UpAxis::Z, out, file);
    out += "ObjectEnd\n";
    generator::flush_if_large(out, file);
  }
  out += "\n" + trees.instances;
}

// The OBJ meshes, one trianglemesh per mesh and material, with the materials named in
// `mesh_materials`.
void write_meshes(const scene::Scene& built,
                  const std::vector<std::vector<std::string>>& mesh_materials, std::string& out,
                  AtomicFile& file) {
  for (std::size_t i = 0; i < built.meshes.size(); ++i) {
    const scene::MeshObject& m = built.meshes[i];
    const bool has_normals = !m.normals.empty();
    for (std::size_t k = 0; k < m.materials.size(); ++k) {
      // Each triangle's corners on their own (the OBJ's normals are indexed apart from its points).
      std::string p, n;
      std::size_t corners = 0;
      for (std::size_t t = 0; t < m.material.size(); ++t) {
        if (m.material[t] != k) continue;
        for (std::size_t c = 0; c < 3; ++c) {
          p += triple(m.positions[m.indices[3 * t + c]]) + " ";
          if (has_normals) {
            const std::uint32_t ni = m.normal_indices[3 * t + c];
            // A corner without a normal: the flat triangle's.
            const glm::vec3 flat = glm::normalize(
                glm::cross(m.positions[m.indices[3 * t + 1]] - m.positions[m.indices[3 * t]],
                           m.positions[m.indices[3 * t + 2]] - m.positions[m.indices[3 * t]]));
            n += triple(ni < m.normals.size() ? m.normals[ni] : flat) + " ";
          }
          ++corners;
        }
      }
      if (corners == 0) continue;
      out += "AttributeBegin # " + built.object_names.at(m.object_id - 1) + "\n  NamedMaterial \"" +
             mesh_materials[i][k] + "\"\n  Shape \"trianglemesh\" \"point3 P\" [ " + p + "]";
      if (has_normals) out += "\n    \"normal N\" [ " + n + "]";
      out += "\n    \"integer indices\" [ ";
      for (std::size_t c = 0; c < corners; ++c) out += std::to_string(c) + " ";
      out += "]\nAttributeEnd\n";
      generator::flush_if_large(out, file);
    }
  }
}

// The ground: the plane z = 0, 10 km each way, in material `ground` (on a terrain, a millimetre
// below, as arbor's World has it, so the terrain's edge wins where they meet); with patches, the
// square around `centre` in their baked image (ground_image) and the rest around it in `ground`.
std::string ground_text(const std::string& ground, bool patches, bool terrain, double floor,
                        glm::vec2 centre, const std::string& ground_image) {
  if (!patches) {
    const std::string z = terrain ? number(floor - 0.001) : "0";
    return "AttributeBegin # ground: the plane z = " + z + ", 10 km each way\n  NamedMaterial \"" +
           ground + "\"\n  Shape \"trianglemesh\" \"point3 P\" [ -1e4 -1e4 " + z + "  1e4 -1e4 " +
           z + "  1e4 1e4 " + z + "  -1e4 1e4 " + z +
           " ]"
           " \"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n";
  }
  const float x0 = centre.x - kGroundHalf, x1 = centre.x + kGroundHalf;
  const float y0 = centre.y - kGroundHalf, y1 = centre.y + kGroundHalf;
  const std::string inner = number(x0) + " " + number(y0) + " 0  " + number(x1) + " " + number(y0) +
                            " 0  " + number(x1) + " " + number(y1) + " 0  " + number(x0) + " " +
                            number(y1) + " 0";
  return "# the ground's patches near the camera, baked (" + file_name(ground_image) +
         "); beyond, their mean\n"
         "Texture \"ground patches\" \"spectrum\" \"imagemap\" \"string filename\" \"" +
         file_name(ground_image) +
         "\"\nMakeNamedMaterial \"ground patches\" \"string type\" \"diffuse\" \"texture "
         "reflectance\" \"ground patches\"\n"
         "AttributeBegin # ground near the camera: " +
         number(2.0f * kGroundHalf) +
         " m square\n  NamedMaterial \"ground patches\"\n"
         "  Shape \"trianglemesh\" \"point3 P\" [ " +
         inner +
         " ] \"point2 uv\" [ 0 0  1 0  1 1  0 1 ]"
         " \"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n"
         "AttributeBegin # the rest of the ground: the plane z = 0 to 10 km each way, around that "
         "square\n"
         "  NamedMaterial \"" +
         ground +
         "\"\n  Shape \"trianglemesh\" \"point3 P\" [ -1e4 -1e4 0  1e4 -1e4 0  1e4 1e4 0  -1e4 1e4 "
         "0  " +
         inner +
         " ] \"integer indices\" [ 0 1 5  0 5 4  1 2 6  1 6 5  2 3 7  2 7 6  3 0 4  3 4 7 "
         "]\nAttributeEnd\n";
}

// One grid of the terrain (the square, or its surround): its mesh and albedo image written at
// `mesh` and `albedo`, and the pbrt text that names them.
std::string grid_text(const scene::Terrain& grid, const materials::GroundMaterial& ground,
                      const Colors& colors, const PbrtColorSpace& space, const std::string& mesh,
                      const std::string& albedo, const std::string& name, PbrtExport& result) {
  std::size_t clamped = 0;
  const imaging::Image img = terrain_albedo(grid, ground, colors.to_pbrt, clamped);
  if (clamped > 0) {
    result.clamped.push_back("the " + name + "'s albedo (" + std::to_string(clamped) + " of " +
                             std::to_string(img.beauty.size()) + " texels)");
  }
  imaging::OutputSpec output;
  output.colorspace = "Linear";
  output.pixel_type = imaging::PixelType::Half;
  imaging::ExrMetadata meta;
  meta.scene = "arbor " + name + " albedo for pbrt-v4 (its soil, rock and ground), linear in " +
               "pbrt's colour space " + std::string(space.name);
  meta.chromaticities = space.chromaticities;
  meta.render_attributes = false;
  imaging::write_exr(img, output, meta, albedo);
  result.written.push_back(albedo);
  write_terrain_ply(grid, mesh);
  result.written.push_back(mesh);
  return "# the " + name + ": its grid's triangles (" + file_name(mesh) +
         "), its albedo by slope, curvature and altitude baked (" + file_name(albedo) +
         ")\nTexture \"" + name + " albedo\" \"spectrum\" \"imagemap\" \"string filename\" \"" +
         file_name(albedo) + "\"\nMakeNamedMaterial \"" + name +
         "\" \"string type\" \"diffuse\" \"texture reflectance\" \"" + name +
         " albedo\"\nAttributeBegin # " + name + "\n  NamedMaterial \"" + name +
         "\"\n  Shape \"plymesh\" \"string filename\" \"" + file_name(mesh) + "\"\nAttributeEnd\n";
}

// The terrain: the square (OUT.terrain.ply, OUT.terrain.exr), its surround (OUT.surround.ply,
// OUT.surround.exr) and the skirt between them (rock), each written, and the pbrt text.
std::string terrain_text(const scene::Scene& scene, const Colors& colors,
                         const PbrtColorSpace& space, const std::string& out, PbrtExport& result) {
  const materials::GroundMaterial* ground = scene.ground.as<materials::GroundMaterial>();
  if (!ground) throw std::logic_error("a terrain whose material is not the ground's");
  const scene::Terrain& t = scene.terrain;
  std::string text = grid_text(t, *ground, colors, space, terrain_mesh_path_for(out),
                               terrain_albedo_path_for(out), "terrain", result);
  if (!t.surround()) return text;
  text += grid_text(*t.surround(), *ground, colors, space, surround_mesh_path_for(out),
                    surround_albedo_path_for(out), "surround", result);
  text +=
      "AttributeBegin # the skirt from the terrain's edge down under the surround: rock\n"
      "  Material \"diffuse\" " +
      colors.rgb("reflectance", ground->rock_albedo, "the skirt's rock") +
      "\n  Shape \"trianglemesh\" \"point3 P\" [ ";
  for (const glm::vec3& p : t.skirt_positions()) text += triple(p) + " ";
  text += "]\n    \"integer indices\" [ ";
  for (std::uint32_t i : t.skirt_indices()) text += std::to_string(i) + " ";
  return text + "]\nAttributeEnd\n";
}

}  // namespace

PbrtColorSpace pbrt_color_space_of(const imaging::ColorPipeline& color) {
  const std::vector<float> linear = color.chromaticities("scene_linear");
  if (linear.empty()) {
    throw InputError(
        {}, "the OCIO config " + color.config_path() +
                ": arbor cannot tell the primaries of its scene_linear space, so it cannot "
                "state the scene's colours in a pbrt-v4 colour space");
  }
  return pbrt_color_space_for(linear);
}

PbrtExport write_pbrt_scene(const scene::Scene& scene, const scene::RenderInput& input,
                            const imaging::ColorPipeline& color, const std::string& out,
                            int sky_resolution) {
  const std::vector<float> linear = color.chromaticities("scene_linear");
  PbrtExport result;
  const PbrtColorSpace space = pbrt_color_space_of(color);
  result.space = space.name;
  Colors colors;
  colors.clamped = &result.clamped;
  if (space.chromaticities != linear)
    colors.to_pbrt = imaging::rgb_to_rgb(linear, space.chromaticities);

  const Sky sky(input.sky, input.sun, color.xyz_to_scene_linear(), kSkyMapWidth,
                input.render.aerial_perspective);
  const std::string sky_path = sky_path_for(out), ground_path = ground_path_for(out);

  AtomicFile file(out);
  std::string text = camera_text(input, space, static_cast<bool>(colors.to_pbrt), out);
  text += lights_text(input, sky, colors, sky_path);
  // Materials first, then the trees, the meshes, the ground.
  Materials materials(colors);
  const TreeObjects trees = tree_objects(scene, materials);
  std::vector<std::vector<std::string>> mesh_materials;
  for (const scene::MeshObject& m : scene.meshes) {
    std::vector<std::string> names;
    for (std::size_t k = 0; k < m.materials.size(); ++k) {
      names.push_back(
          materials.name_of(m.materials[k], scene.material_names.at(m.material_ids[k] - 1)));
    }
    mesh_materials.push_back(names);
  }
  const std::string ground = scene.has_ground ? materials.name_of(scene.ground, "ground") : "";
  // The rocks' lichen-spotted pattern has no pbrt counterpart: its mean.
  const materials::GroundMaterial* rock = scene.rocks.material.as<materials::GroundMaterial>();
  const std::string rock_material =
      scene.rocks.empty() || !rock
          ? ""
          : materials.name_of(materials::DiffuseMaterial{mean_rock_albedo(*rock)}, "rocks");
  text += "\n" + materials.text() + "\n";
  write_trees(scene, trees, text, file);
  write_meshes(scene, mesh_materials, text, file);
  const materials::GroundMaterial* patched = scene.ground.as<materials::GroundMaterial>();
  // On a terrain the ground under the camera is the terrain's (its albedo image holds the
  // patches); the plane around it takes their mean.
  const bool ground_patches =
      scene.has_ground && scene.terrain.empty() && patched && patched->cover > 0.0f;
  // Centred on the camera, on a whole metre (the same export twice gives the same files).
  const glm::vec2 ground_centre(std::round(static_cast<float>(input.camera.position[0])),
                                std::round(static_cast<float>(input.camera.position[1])));
  if (scene.has_ground)
    text += ground_text(ground, ground_patches, !scene.terrain.empty(), scene.terrain.floor(),
                        ground_centre, ground_path);
  if (!scene.terrain.empty()) text += terrain_text(scene, colors, space, out, result);
  if (!scene.rocks.empty()) text += rocks_text(scene.rocks, rock_material);

  // The sky goes first: a failed write of the scene leaves at most a new sky beside the old
  // scene, never a scene naming a sky that is not there.
  result.written.insert(result.written.begin(), out);
  if (!sky.empty()) {
    write_sky_exr(sky, colors, space, sky_resolution, scene.has_ground, sky_path);
    result.written.push_back(sky_path);
  }
  if (ground_patches) {
    write_ground_exr(*patched, colors, space, ground_centre, ground_path);
    result.written.push_back(ground_path);
  }
  file.write(text);
  file.commit();
  return result;
}

}  // namespace arbor::tracer
