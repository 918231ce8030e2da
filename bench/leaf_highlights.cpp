// The close-up's highlight measure (issue 45; docs/geometry.md, "Shaped leaves"): how much of
// each leaf a sun glint whitens. Reads a scene and the EXR (scene-linear) and PNG (display) that
// `arbor render` wrote for it, finds the leaf under every pixel's centre by tracing the camera's
// ray through the scene's own world (each leaf of each tree its own id), and prints one JSON
// object:
//   leaves               leaves covering at least 20 pixel centres
//   highlight_p50/p95/max over those leaves, the fraction of its pixels brighter than 3 × the
//                        leaf's median luminance (linear Rec. 709 Y of the EXR)
//   over_half            of those leaves, how many have a highlight over half the leaf
//   white_leaves         of those leaves, how many are near-white (below) over half their pixels:
//                        a glint that whitens the whole leaf, which the highlight (relative to
//                        the leaf's own median) cannot see
//   tree_pixels          pixels whose centre sees a tree (bark or leaf)
//   near_white           fraction of them near-white and colourless in the PNG (every channel
//                        ≥ 0.85, max − min ≤ 0.08)
// Usage: leaf_highlights SCENE.toml [EXR PNG]  (default: the scene's [output] paths)
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "formats/scene_file.h"
#include "scene/render_input.h"
#include "scene/scene.h"
#include "tracer/camera.h"
#include "tracer/embree/embree_device.h"
#include "tracer/embree/world.h"

namespace {

std::vector<float> read_rgb(const std::string& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::fprintf(stderr, "leaf_highlights: cannot read %s\n", path.c_str());
    std::exit(2);
  }
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::vector<float> all(static_cast<std::size_t>(width) * height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data());
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) {
    for (int c = 0; c < 3; ++c)
      rgb[3 * p + c] = all[p * spec.nchannels + std::min(c, spec.nchannels - 1)];
  }
  return rgb;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 4) {
    std::fprintf(stderr, "usage: leaf_highlights SCENE.toml [EXR PNG]\n");
    return 2;
  }
  const arbor::spec::SceneDesc desc = arbor::formats::load_scene(argv[1]);
  const std::string exr = argc == 4 ? argv[2] : desc.output.exr;
  const std::string png = argc == 4 ? argv[3] : desc.output.png;
  int w = 0, h = 0, pw = 0, ph = 0;
  const std::vector<float> linear = read_rgb(exr, w, h);
  const std::vector<float> display = read_rgb(png, pw, ph);
  if (pw != w || ph != h || w != desc.render.width || h != desc.render.height) {
    std::fprintf(stderr, "leaf_highlights: the images are not the scene's size\n");
    return 2;
  }
  const std::unique_ptr<const arbor::scene::Scene> built =
      arbor::scene::build_scene(desc, ARBOR_SOURCE_DIR "/imaging/ocio/config.ocio");
  const arbor::tracer::EmbreeDevice device("threads=2");
  const arbor::tracer::World world(*built, device);
  const arbor::scene::RenderInput input = arbor::scene::render_input(desc);
  const arbor::tracer::Camera camera(input.camera, w, h);

  std::map<std::pair<int, int>, std::vector<double>> leaves;  // (instance, leaf) → luminances
  std::map<std::pair<int, int>, std::size_t> white;           // its near-white pixels
  std::size_t tree_pixels = 0, near_white = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      arbor::tracer::Ray ray = camera.generate({x + 0.5f, y + 0.5f}, {0.5f, 0.5f});
      arbor::tracer::WorldHit hit;
      if (!world.intersect(ray, hit) || hit.instance < 0) continue;
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      ++tree_pixels;
      const float* d = &display[3 * p];
      const float lo = std::min({d[0], d[1], d[2]}), hi = std::max({d[0], d[1], d[2]});
      const bool is_white = lo >= 0.85f && hi - lo <= 0.08f;
      near_white += is_white ? 1u : 0u;
      if (hit.surface.leaf < 0) continue;
      white[{hit.instance, hit.surface.leaf}] += is_white ? 1u : 0u;
      const float* l = &linear[3 * p];
      leaves[{hit.instance, hit.surface.leaf}].push_back(0.2126 * l[0] + 0.7152 * l[1] +
                                                         0.0722 * l[2]);
    }
  }
  std::vector<double> fractions;
  std::size_t over_half = 0, white_leaves = 0;
  for (auto& [id, lum] : leaves) {
    if (lum.size() < 20) continue;
    const double median = quantile(lum, 0.5);
    std::size_t bright = 0;
    for (double v : lum) bright += v > 3.0 * median ? 1u : 0u;
    const double f = static_cast<double>(bright) / static_cast<double>(lum.size());
    fractions.push_back(f);
    over_half += f > 0.5 ? 1u : 0u;
    white_leaves += 2 * white[id] > lum.size() ? 1u : 0u;
  }
  std::printf(
      "{\"scene\": \"%s\", \"leaves\": %zu, \"highlight_p50\": %.4f, \"highlight_p95\": %.4f, "
      "\"highlight_max\": %.4f, \"over_half\": %zu, \"white_leaves\": %zu, \"tree_pixels\": %zu, "
      "\"near_white\": %.4f}\n",
      argv[1], fractions.size(), quantile(fractions, 0.5), quantile(fractions, 0.95),
      quantile(fractions, 1.0), over_half, white_leaves, tree_pixels,
      tree_pixels ? static_cast<double>(near_white) / static_cast<double>(tree_pixels) : 0.0);
  return 0;
}
