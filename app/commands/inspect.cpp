// `arbor inspect`: build the scene (trees grown, community simulated, meadow and rocks placed),
// then describe what was built, as text or JSON.
#include "app/commands/inspect.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

#include "common/json.h"
#include "common/math.h"
#include "common/progress.h"
#include "common/range.h"
#include "formats/scene_file.h"
#include "scene/render_budget.h"
#include "scene/scene.h"
#include "tracer/film.h"

namespace arbor::app {

namespace {

// The size classes, by the placed tree's height: what a stand's structure is read by.
constexpr std::array<double, 3> kClassTops{1.0, 5.0, 15.0};
constexpr std::array<const char*, 4> kClassNames{"under 1 m", "1 to 5 m", "5 to 15 m", "over 15 m"};

int size_class(double height) {
  int c = 0;
  while (c < 3 && height >= kClassTops[static_cast<std::size_t>(c)]) ++c;
  return c;
}

// 1234567 → "1,234,567".
std::string grouped(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string megabytes(std::uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MB", static_cast<double>(bytes) / double(1 << 20));
  return buf;
}

// One placed tree as inspect reports it.
struct Placed {
  std::string species;
  int prototype = 0, variant = -1;  // variant: the community's, -1 for trees and forests
  double age = -1.0;                // years; the community's plants only
  glm::dvec3 position{0.0};         // the base of the trunk's axis
  double rotation = 0.0, scale = 1.0, ground = 0.0, height = 0.0, crown = 0.0;
};

std::vector<Placed> placed_trees(const scene::Scene& s) {
  std::vector<Placed> out;
  out.reserve(s.instances.size());
  for (const scene::TreeInstance& t : s.instances) {
    Placed p;
    const std::string& name = s.object_names[t.object_id - 1];  // "<species>.<n>"
    p.species = name.substr(0, name.find_last_of('.'));
    p.prototype = t.prototype;
    p.position = glm::dvec3(t.to_world[3]);
    p.scale = glm::length(glm::dvec3(t.to_world[0]));
    p.rotation = std::atan2(t.to_world[0][1], t.to_world[0][0]) * 180.0 / kPi;
    if (p.rotation < 0.0) p.rotation += 360.0;
    p.ground = s.terrain.height(p.position.x, p.position.y);
    p.height = t.extent.height;
    p.crown = t.extent.radius;
    out.push_back(p);
  }
  for (const scene::Scene::CommunityPlant& c : s.community) {
    out[c.instance].variant = c.variant;
    out[c.instance].age = c.age;
  }
  return out;
}

struct SpeciesCount {
  std::uint64_t total = 0;
  std::array<std::uint64_t, 4> classes{};
};

std::map<std::string, SpeciesCount> counts_of(const std::vector<Placed>& trees) {
  std::map<std::string, SpeciesCount> counts;
  for (const Placed& p : trees) {
    SpeciesCount& c = counts[p.species];
    ++c.total;
    ++c.classes[static_cast<std::size_t>(size_class(p.height))];
  }
  return counts;
}

std::string terrain_line(const spec::SceneDesc& desc, const scene::Terrain& t) {
  double lo = 1e300, hi = -1e300;
  for (int j = 0; j < t.rows(); ++j)
    for (int i = 0; i < t.columns(); ++i) {
      lo = std::min(lo, static_cast<double>(t.at(i, j)));
      hi = std::max(hi, static_cast<double>(t.at(i, j)));
    }
  const glm::dvec2 e = t.extent();
  return std::string(spec::kTerrainKindNames[static_cast<std::size_t>(desc.terrain.kind)]) + ", " +
         short_number(e.x) + " × " + short_number(e.y) + " m at " + short_number(t.spacing()) +
         " m (" +
         grouped(static_cast<std::uint64_t>(t.columns()) * static_cast<std::uint64_t>(t.rows())) +
         " vertices), heights " + short_number(std::round(lo * 10) / 10) + " to " +
         short_number(std::round(hi * 10) / 10) + " m";
}

JsonObject instance_json(const Placed& p) {
  JsonObject o;
  o.text("species", p.species).integer("prototype", static_cast<long long>(p.prototype));
  if (p.variant >= 0) o.integer("variant", static_cast<long long>(p.variant));
  if (p.age >= 0.0) o.number("age", p.age, 6);
  o.numbers("position", {p.position.x, p.position.y, p.position.z}, 9)
      .number("rotation", p.rotation, 6)
      .number("scale", p.scale, 6)
      .number("ground", p.ground, 9)
      .number("height", p.height, 6)
      .number("crown_radius", p.crown, 6);
  return o;
}

void print_json(const InspectRequest& a, const spec::SceneDesc& desc, const scene::Scene& s,
                const std::vector<Placed>& trees, const scene::MemoryEstimate& memory) {
  JsonObject root;
  root.text("scene", a.scene);
  if (!s.terrain.empty()) {
    const glm::dvec2 o = s.terrain.origin(), e = s.terrain.extent();
    root.object(
        "terrain",
        JsonObject()
            .text("kind", spec::kTerrainKindNames[static_cast<std::size_t>(desc.terrain.kind)])
            .numbers("area", {o.x, o.y, o.x + e.x, o.y + e.y})
            .number("spacing", s.terrain.spacing())
            .integer("columns", static_cast<long long>(s.terrain.columns()))
            .integer("rows", static_cast<long long>(s.terrain.rows())));
  }
  JsonObject species;
  for (const auto& [name, c] : counts_of(trees)) {
    JsonObject classes;
    for (std::size_t k = 0; k < c.classes.size(); ++k)
      classes.integer(kClassNames[k], static_cast<unsigned long long>(c.classes[k]));
    species.object(name, JsonObject()
                             .integer("instances", static_cast<unsigned long long>(c.total))
                             .object("size_classes", classes));
  }
  root.integer("prototypes", static_cast<unsigned long long>(s.stats.prototypes))
      .object("species", species)
      .object("meadow",
              JsonObject()
                  .integer("blades", static_cast<unsigned long long>(s.meadow.placed_blades()))
                  .integer("distinct_blades",
                           static_cast<unsigned long long>(s.meadow.distinct_blades())))
      .object("rocks",
              JsonObject()
                  .integer("rocks", static_cast<unsigned long long>(s.rocks.placements.size()))
                  .integer("shapes", static_cast<unsigned long long>(s.rocks.shapes.size())))
      .object(
          "memory",
          JsonObject()
              .integer("geometry_bytes", static_cast<unsigned long long>(s.stats.geometry_bytes))
              .integer("instance_bytes", static_cast<unsigned long long>(memory.instance_bytes))
              .integer("image_bytes", static_cast<unsigned long long>(memory.image_bytes))
              .integer("meadow_bytes", static_cast<unsigned long long>(memory.meadow_bytes))
              .integer("terrain_bytes", static_cast<unsigned long long>(memory.terrain_bytes)))
      .number("build_seconds", s.stats.build_seconds, 4)
      .number("simulation_seconds", s.stats.simulation_seconds, 4);
  std::vector<JsonObject> list;
  list.reserve(trees.size());
  for (const Placed& p : trees) list.push_back(instance_json(p));
  root.objects("instances", list);
  std::printf("%s\n", root.str().c_str());
}

void print_text(const InspectRequest& a, const spec::SceneDesc& desc, const scene::Scene& s,
                const std::vector<Placed>& trees, const scene::MemoryEstimate& memory) {
  std::printf("scene     %s\n", a.scene.c_str());
  if (!s.terrain.empty()) std::printf("terrain   %s\n", terrain_line(desc, s.terrain).c_str());
  const std::map<std::string, SpeciesCount> counts = counts_of(trees);
  std::printf("trees     %s instances of %s prototypes, %zu species\n",
              grouped(trees.size()).c_str(), grouped(s.stats.prototypes).c_str(), counts.size());
  if (!counts.empty()) {
    std::printf("  %-24s %10s", "species", "instances");
    for (const char* c : kClassNames) std::printf(" %10s", c);
    std::printf("\n");
    for (const auto& [name, c] : counts) {
      std::printf("  %-24s %10s", name.c_str(), grouped(c.total).c_str());
      for (const std::uint64_t k : c.classes) std::printf(" %10s", grouped(k).c_str());
      std::printf("\n");
    }
  }
  if (!s.meadow.empty()) {
    std::printf("meadow    %s blades placed (%s distinct)\n",
                grouped(s.meadow.placed_blades()).c_str(),
                grouped(s.meadow.distinct_blades()).c_str());
  }
  if (!s.rocks.empty()) {
    std::array<std::uint64_t, 4> by{};  // under 0.5 m, 0.5 to 1 m, 1 to 2 m, over 2 m
    for (const scene::RockPlacement& r : s.rocks.placements)
      ++by[r.diameter < 0.5f ? 0 : r.diameter < 1.0f ? 1 : r.diameter < 2.0f ? 2 : 3];
    std::printf(
        "rocks     %s of %zu shapes: %s under 0.5 m across, %s 0.5 to 1 m, %s 1 to 2 m, %s over "
        "2 m\n",
        grouped(s.rocks.placements.size()).c_str(), s.rocks.shapes.size(), grouped(by[0]).c_str(),
        grouped(by[1]).c_str(), grouped(by[2]).c_str(), grouped(by[3]).c_str());
  }
  std::printf(
      "memory    about %s before Embree's structures: geometry %s (trees, meshes, terrain, "
      "meadow, rocks), instances %s, image %s\n",
      megabytes(s.stats.geometry_bytes + memory.instance_bytes + memory.image_bytes).c_str(),
      megabytes(s.stats.geometry_bytes).c_str(), megabytes(memory.instance_bytes).c_str(),
      megabytes(memory.image_bytes).c_str());
  std::printf("built in %.2f s (the community's simulation %.2f s of it)\n", s.stats.build_seconds,
              s.stats.simulation_seconds);
  if (!a.instances) return;
  std::printf("\n# species\tprototype\tvariant\tage\tx\ty\tz\trotation\tscale\tground\theight\n");
  for (const Placed& p : trees) {
    std::printf("%s\t%d\t%d\t%.0f\t%.3f\t%.3f\t%.3f\t%.1f\t%.4f\t%.3f\t%.2f\n", p.species.c_str(),
                p.prototype, p.variant, p.age, p.position.x, p.position.y, p.position.z, p.rotation,
                p.scale, p.ground, p.height);
  }
}

}  // namespace

CLI::App* add_inspect_command(CLI::App& app, InspectRequest& request) {
  CLI::App* cmd = app.add_subcommand(
      "inspect",
      "Build a scene without rendering it and say what it holds: its terrain, every tree "
      "instance, counts per species and size class, the meadow, the memory estimate");
  cmd->add_option("SCENE", request.scene, "scene file (.toml)")->required();
  cmd->add_flag("--json", request.json,
                "print everything as one JSON object, every instance included");
  cmd->add_flag("--instances", request.instances,
                "list every instance too, one a line, tab-separated (text report)");
  return cmd;
}

int inspect_command(const InspectRequest& a) {
  const spec::SceneDesc desc = formats::load_scene(a.scene);
  Progress progress("build", 1);
  const std::unique_ptr<const scene::Scene> built = scene::build_scene(
      desc, a.ocio_config, &progress, 0, static_cast<unsigned>(std::max(0, desc.render.threads)));
  progress.finish();
  const std::vector<Placed> trees = placed_trees(*built);
  scene::MemoryEstimate memory = scene::estimate_render_memory(desc, tracer::Film::costs());
  memory.instances = built->instances.size();  // the community's plants counted too
  memory.instance_bytes = memory.instances * scene::kBytesPerInstance;
  if (a.json)
    print_json(a, desc, *built, trees, memory);
  else
    print_text(a, desc, *built, trees, memory);
  return 0;
}

}  // namespace arbor::app
