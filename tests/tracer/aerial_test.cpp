// Aerial perspective (tracer/lights/aerial.h): the table against the atmosphere model it is made
// from, and a grey card rendered at 0 m and 5 km against the table's transmittance and path
// radiance.
#include "tracer/lights/aerial.h"

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/math.h"
#include "spec/scene_desc.h"
#include "scene/render_input.h"
#include "test_world.h"
#include "tracer/lights/nishita.h"
#include "tracer/lights/sky.h"
#include "tracer/render.h"

namespace arbor::tracer {

namespace {

const imaging::ColorTransform kIdentity = [](float*) {};

glm::dvec3 direction(double elevation_deg, double azimuth_deg) {
  const double e = radians(elevation_deg), a = radians(azimuth_deg);
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

}  // namespace

// The table's entries, looked up between its cells and slices, against the model's own path
// integral (256 steps) in directions and at distances off the grid: within 1 % of the in-scattered
// light, and of the transmittance within 0.2 % up to 5 km and 1 % at 41 km; at 0 m the air does
// nothing.
TEST(AerialPerspective, TheTableIsTheModelsPathIntegral) {
  Atmosphere air;
  air.dust_density = 2.65;
  air.multiple_scattering = true;
  air.ground_albedo = 0.14;
  const glm::dvec3 sun = direction(40.0, 20.0);
  const NishitaSky model(air, sun, 1.0);
  // XYZ as the rendering space, balanced so that the sun outside the atmosphere is (Y, Y, Y).
  const glm::dvec3 space = model.extraterrestrial_xyz();
  const auto balanced = [&](const glm::dvec3& xyz) { return glm::vec3(xyz / space * space.y); };
  const AerialPerspective table(model, balanced, space.y);
  for (const glm::dvec3& d : {direction(0.7, 33.0), direction(8.3, 200.0), direction(-3.1, 95.0)}) {
    for (double distance : {130.0, 2300.0, 5000.0, 41000.0}) {
      const NishitaSky::Segment exact = model.segments(d, {distance}, 256)[0];
      const AerialPerspective::Sample got = table.at(glm::vec3(d), static_cast<float>(distance));
      for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(testing::Message() << "direction " << d.x << " " << d.y << " " << d.z << ", "
                                        << distance << " m, component " << k);
        const double in = exact.inscattered[k] / space[k] * space.y;
        EXPECT_NEAR(got.inscattered[k], in, 0.01 * in);
        const double t = exact.transmitted[k] / space[k];
        EXPECT_NEAR(got.transmittance[k], t, (distance <= 5000.0 ? 0.002 : 0.01) * t);
      }
    }
    const AerialPerspective::Sample none = table.at(glm::vec3(d), 0.0f);
    EXPECT_EQ(none.inscattered, glm::vec3(0.0f));
    EXPECT_NEAR(none.transmittance.x, 1.0f, 1e-6f);
    EXPECT_NEAR(none.transmittance.z, 1.0f, 1e-6f);
  }
}

namespace {

// A grey card facing the camera `distance` metres away along +x, filling a 1° view, lit by a sun
// at 40° under the atmosphere sky; no ground.
spec::SceneDesc card_scene(double distance, bool aerial) {
  const std::string obj = ::testing::TempDir() + "card.obj";
  const double h = 0.05 * distance;
  std::ofstream(obj) << "v " << distance << " " << -h << " " << -h << "\nv " << distance << " " << h
                     << " " << -h << "\nv " << distance << " " << h << " " << h << "\nv "
                     << distance << " " << -h << " " << h << "\ng card\nf 1 4 3 2\n";
  spec::SceneDesc s;
  s.render.width = s.render.height = 4;
  s.render.spp = 16;
  s.render.aerial_perspective = aerial;
  s.camera.position = {0.0, 0.0, 0.0};
  s.camera.look_at = {1.0, 0.0, 0.0};
  s.camera.fov = 1.0;
  s.camera.focus_distance = distance;
  s.sun.elevation = 40.0;
  s.sun.azimuth = 180.0;  // behind the camera: the card's face is lit
  s.sky.model = spec::SkyModel::Atmosphere;
  s.ground.enabled = false;
  spec::MeshDesc m;
  m.path = obj;
  m.up = "z";
  spec::MeshMaterialDesc grey;
  grey.kind = "diffuse";
  grey.albedo = {0.18, 0.18, 0.18};
  m.materials["card"] = grey;
  s.meshes.push_back(m);
  return s;
}

imaging::Image render_card(const spec::SceneDesc& scene, const Sky& sky) {
  const EmbreeDevice device("");
  const TestWorld test_world(scene, device);
  imaging::RenderStats stats;
  return render_image(scene::render_input(scene), test_world.world, sky, kIdentity, stats);
}

}  // namespace

// The same paths with and without the air (it draws no random numbers): every pixel of the card
// at 5 km is the card's own radiance × the table's transmittance + its in-scattered light, which
// are 10–25 % changes there; at 0.5 m the air changes nothing a user could see.
TEST(AerialPerspective, AGreyCardFadesByTheAtmospheresTransmittanceAndPathRadiance) {
  for (double distance : {0.5, 5000.0}) {
    const spec::SceneDesc off = card_scene(distance, false), on = card_scene(distance, true);
    const Sky sky_off(off.sky, off.sun, xyz_to_scene_linear(), 128);
    const Sky sky_on(on.sky, on.sun, xyz_to_scene_linear(), 128, true);
    ASSERT_NE(sky_on.aerial(), nullptr);
    EXPECT_EQ(sky_off.aerial(), nullptr);
    const imaging::Image a = render_card(off, sky_off), b = render_card(on, sky_on);
    const AerialPerspective::Sample air =
        sky_on.aerial()->at(glm::vec3(1, 0, 0), static_cast<float>(distance));
    std::printf("  %g m: transmittance %.4f %.4f %.4f, in-scattered %.4g %.4g %.4g, card %.4g\n",
                distance, air.transmittance.x, air.transmittance.y, air.transmittance.z,
                air.inscattered.x, air.inscattered.y, air.inscattered.z, a.beauty[0].y);
    for (std::size_t p = 0; p < a.beauty.size(); ++p) {
      ASSERT_GT(a.depth[p], 0.0f) << "pixel " << p << " misses the card";
      for (int c = 0; c < 3; ++c) {
        const float expected = a.beauty[p][c] * air.transmittance[c] + air.inscattered[c];
        // 0.2 %: the pixels look up to 0.5° from the card's centre, which the table resolves.
        EXPECT_NEAR(b.beauty[p][c], expected, 2e-3f * expected) << "pixel " << p << ", " << c;
      }
    }
    if (distance > 1000.0) {
      // Bluish air in front of a grey card: the card loses red more than blue, gains blue more.
      EXPECT_LT(air.transmittance.x, 0.95f);
      EXPECT_GT(air.inscattered.z, air.inscattered.x);
      EXPECT_GT(std::fabs(b.beauty[0].y / a.beauty[0].y - 1.0f), 0.05f);
    } else {
      EXPECT_NEAR(air.transmittance.y, 1.0f, 1e-4f);
      EXPECT_NEAR(b.beauty[0].y, a.beauty[0].y, 1e-4f * a.beauty[0].y);
    }
  }
}

}  // namespace arbor::tracer
