// Textured diffuse surfaces in whole renders: a quad of the quadrant texture (texture_images.h)
// under a light straight above of irradiance pi reflects radiance equal to the texture's colour
// (albedo E / pi at cos 1), exactly, in every integrator; the first-hit albedo AOV is the same
// colour; the image is bitwise the same for any thread count. OBJ meshes and spheres wear
// textures by their own texture coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"
#include "tests/support/test_directory.h"
#include "tests/support/texture_images.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kResolution = 16;

// The quad (2 wide, at distance 2) fills the view exactly, so pixel (x, y) sees texture
// coordinates ((x + 0.5) / 16, (y + 0.5) / 16) at its centre.
Scene textured_quad(const fs::path& dir, json shape = {{"type", "quad"}, {"size", 2.0}}) {
  shape["material"] = {{"type", "diffuse"}, {"albedo_texture", "quadrants.exr"}};
  const json doc = {{"camera",
                     {{"position", {0.0, 2.0, 0.0}},
                      {"look_at", {0.0, 0.0, 0.0}},
                      {"up", {0.0, 0.0, -1.0}},
                      {"fov", 2 * std::atan(0.5) * 180 / std::numbers::pi},
                      {"resolution", {kResolution, kResolution}}}},
                    {"shapes", {shape}},
                    {"lights",
                     {{{"type", "directional"},
                       {"direction", {0.0, 1.0, 0.0}},
                       {"irradiance", std::numbers::pi}}}}};
  return load_scene_json(doc, "textured quad", dir.string()).scene;
}

class TextureRender : public test::QuadrantTextureTest {
 protected:
  TextureRender() : QuadrantTextureTest("test_texture_render") {}
};

// An OBJ mesh of the quad's corners whose vt coordinates (v up the image) name the quad's
// texture coordinates renders the quad's image exactly.
TEST_F(TextureRender, ObjTextureCoordinatesRenderAsTheQuadDoes) {
  std::ofstream(dir_ / "quad.obj") << "v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\n"
                                      "vt 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n"
                                      "f 1/1 2/2 3/3 4/4\n";
  const Scene quad = textured_quad(dir_);
  Scene obj = textured_quad(dir_, {{"type", "mesh"}, {"file", "quad.obj"}});
  RenderOptions options;
  options.spp = 4;
  options.seed = 5;
  EXPECT_TRUE(test::bitwise_identical(render(quad, options).film, render(obj, options).film));
}

// A sphere wears the texture like a globe (scene/surface_uv.h): seen from the direction of
// texture coordinates (u, v) and lit from there with irradiance pi, the point facing the camera
// has radiance equal to the texture's colour at (u, v). The quadrant centres check that u grows
// toward +x and v down from +y.
TEST_F(TextureRender, SphereShowsEachQuadrantWhereTheGlobeMappingPutsIt) {
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    const double u = quadrant % 2 == 0 ? 0.25 : 0.75, v = quadrant / 2 == 0 ? 0.25 : 0.75;
    const double phi = (u - 0.5) * 2 * std::numbers::pi, theta = v * std::numbers::pi;
    const json d = {std::sin(theta) * std::sin(phi), std::cos(theta),
                    std::sin(theta) * std::cos(phi)};
    const json doc = {
        {"camera",
         {{"position", {4 * d[0].get<double>(), 4 * d[1].get<double>(), 4 * d[2].get<double>()}},
          {"look_at", {0.0, 0.0, 0.0}},
          {"up", {d[1].get<double>(), -d[0].get<double>(), 0.0}},
          {"fov", 1.0},
          {"resolution", {3, 3}}}},
        {"shapes",
         {{{"type", "sphere"},
           {"center", {0.0, 0.0, 0.0}},
           {"radius", 1.0},
           {"material", {{"type", "diffuse"}, {"albedo_texture", "quadrants.exr"}}}}}},
        {"lights",
         {{{"type", "directional"}, {"direction", d}, {"irradiance", std::numbers::pi}}}}};
    const Scene scene = load_scene_json(doc, "textured sphere", dir_.string()).scene;
    RenderOptions options;
    options.spp = 4;
    options.seed = 7;
    const Film film = render(scene, options).film;
    const Rgb expected = test::quadrant_colour(quadrant);
    // The centre pixel spans 1/3 degree: cosines of at least 0.99999, and texture coordinates
    // within 0.003 of the quadrant's centre.
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(film.mean[4][c], expected[c], 1e-4f) << "quadrant " << quadrant << " ch " << c;
    }
  }
}

// Pixels 2..5 of each quadrant see texture coordinates within its plateau (1/16 .. 7/16 of the
// texture, between its texel centres) over their whole footprint and filter.
TEST_F(TextureRender, QuadShowsTheTextureInEveryIntegrator) {
  const Scene scene = textured_quad(dir_);
  for (const char* integrator : {"pt", "snee", "sla"}) {
    RenderOptions options;
    options.spp = 4;
    options.seed = 3;
    options.integrator = integrator;
    options.aovs = {true, false, false};
    const Film film = render(scene, options).film;
    int checked = 0;
    for (int y = 0; y < kResolution; ++y) {
      for (int x = 0; x < kResolution; ++x) {
        const int in_quadrant_x = x % 8, in_quadrant_y = y % 8;
        if (in_quadrant_x < 2 || in_quadrant_x > 5 || in_quadrant_y < 2 || in_quadrant_y > 5) {
          continue;
        }
        const Rgb expected = test::quadrant_colour((y / 8) * 2 + x / 8);
        const size_t i = static_cast<size_t>(y) * kResolution + x;
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(film.mean[i][c], expected[c], 1e-5f)
              << integrator << " pixel " << x << "," << y << " ch " << c;
          EXPECT_NEAR(film.albedo[i][c], expected[c], 1e-5f)
              << integrator << " albedo AOV " << x << "," << y << " ch " << c;
        }
        ++checked;
      }
    }
    EXPECT_EQ(checked, 64);
  }
}

// A roughness texture sets the GGX alpha at each hit: a conductor or rough dielectric quad whose
// roughness texture is the quadrant image (green channel 0.2, 0.5, 0.7, 0.6) renders, in each
// quadrant's plateau, as the untextured quad of that quadrant's roughness: every pixel's path
// is its own (same random numbers), and only its alpha differs, by at most the rounding of the
// bilinear lookup. Lit by a light from above (light sampling) and a sky (BSDF sampling, MIS).
TEST_F(TextureRender, RoughnessTextureGivesEachQuadrantItsOwnRoughness) {
  const auto quad_of = [&](json material) {
    json doc = {{"camera",
                 {{"position", {0.0, 2.0, 0.0}},
                  {"look_at", {0.0, 0.0, 0.0}},
                  {"up", {0.0, 0.0, -1.0}},
                  {"fov", 2 * std::atan(0.5) * 180 / std::numbers::pi},
                  {"resolution", {kResolution, kResolution}}}},
                {"shapes", {{{"type", "quad"}, {"size", 2.0}, {"material", material}}}},
                {"lights",
                 {{{"type", "cone"},
                   {"direction", {0.3, 1.0, 0.2}},
                   {"half_angle_degrees", 10},
                   {"radiance", 20}},
                  {{"type", "sky"}, {"scale", 0.5}}}}};
    return load_scene_json(doc, "rough quad", dir_.string()).scene;
  };
  for (const json& base : {json{{"type", "conductor"}, {"metal", "gold"}},
                           json{{"type", "dielectric"}, {"ior", 1.5}}}) {
    json textured = base;
    textured["roughness_texture"] = "quadrants.exr";
    RenderOptions options;
    options.spp = 16;
    options.seed = 9;
    const Film film = render(quad_of(textured), options).film;
    for (int q = 0; q < 4; ++q) {
      json plain = base;
      plain["roughness"] = test::quadrant_colour(q).y;
      const Film expected = render(quad_of(plain), options).film;
      for (int y = (q / 2) * 8 + 2; y <= (q / 2) * 8 + 5; ++y) {
        for (int x = (q % 2) * 8 + 2; x <= (q % 2) * 8 + 5; ++x) {
          const size_t i = static_cast<size_t>(y) * kResolution + x;
          for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(film.mean[i][c], expected.mean[i][c], 1e-4f * expected.mean[i][c] + 1e-7f)
                << base["type"] << " quadrant " << q << " pixel " << x << "," << y;
          }
        }
      }
    }
  }
}

// SNEE leaves a boundary with a roughness texture to the path tracer
// (kernels/stages/snee_probe.cpp): a medium behind one renders with `snee` as with `pt`, within
// their standard errors.
TEST_F(TextureRender, SneeAgreesWithPtBehindATexturedRoughBoundary) {
  const json doc = {
      {"camera",
       {{"position", {0.0, 0.0, 4.0}},
        {"look_at", {0.0, 0.0, 0.0}},
        {"fov", 30},
        {"resolution", {16, 16}}}},
      {"shapes",
       {{{"type", "sphere"},
         {"center", {0.0, 0.0, 0.0}},
         {"radius", 1.0},
         {"material",
          {{"type", "dielectric"}, {"roughness", 0.6}, {"roughness_texture", "quadrants.exr"}}},
         {"medium", {{"sigma_s", 2.0}, {"sigma_a", 0.1}}}}}},
      {"lights",
       {{{"type", "cone"},
         {"direction", {1.0, 1.0, 1.0}},
         {"half_angle_degrees", 5},
         {"radiance", 100}}}}};
  const Scene scene = load_scene_json(doc, "rough sphere", dir_.string()).scene;
  const std::vector<bool> mask = test::sphere_mask(scene);
  test::RegionStats stats[2];
  for (int k = 0; k < 2; ++k) {
    RenderOptions options;
    options.spp = 64;
    options.seed = 21;
    options.integrator = k == 0 ? "pt" : "snee";
    stats[k] = test::region_mean(render(scene, options).film, mask);
  }
  const double se = std::hypot(stats[0].standard_error, stats[1].standard_error);
  EXPECT_GT(stats[0].mean, 0.0);
  EXPECT_NEAR(stats[0].mean, stats[1].mean, 4 * se)
      << "pt " << stats[0].mean << " snee " << stats[1].mean << " se " << se;
}

TEST_F(TextureRender, TexturedImageIsTheSameForAnyThreadCount) {
  const Scene scene = textured_quad(dir_);
  RenderOptions one;
  one.spp = 8;
  one.seed = 11;
  one.threads = 1;
  RenderOptions two = one;
  two.threads = 2;
  EXPECT_TRUE(test::bitwise_identical(render(scene, one).film, render(scene, two).film));
}

}  // namespace
}  // namespace snee
