// The new surface materials inside the renderer, against answers known apart from it. Surfaces
// that absorb nothing vanish in a white furnace: a white mirror and a closed diffuse
// transmitter with R + T = 1. A diffuse transmitter lit by a directional light from either side
// shows R E / pi or T E / pi (light sampling only, so exactly), and a rough gold sphere under a
// constant environment shows at the centre of its disk the albedo of the conductor lobe at
// normal incidence, estimated from the BSDF sampler alone (the renderer adds light sampling and
// MIS). Each for pt, snee and sla.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "kernels/physics/bsdf/conductor.h"
#include "scene/metals.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/chi2.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

using nlohmann::json;

constexpr const char* kIntegrators[] = {"pt", "snee", "sla"};

Film render_doc(const json& doc, const char* integrator, int spp) {
  const Scene scene = load_scene_json(doc, "material render", ".").scene;
  RenderOptions options;
  options.spp = spp;
  options.seed = 5;
  options.integrator = integrator;
  options.snee.light_limit_degrees = 180;  // SNEE under any light (docs/method.md 3.11)
  return render(scene, options).film;
}

// A sheet in the xz-plane seen from above, the light straight above (+1) or below (-1) it.
json sheet_scene(float light_side) {
  return {
      {"camera",
       {{"position", {0.0, 3.0, 0.0}},
        {"look_at", {0.0, 0.0, 0.0}},
        {"up", {0.0, 0.0, -1.0}},
        {"fov", 20.0},
        {"resolution", {8, 8}}}},
      {"shapes",
       {{{"type", "quad"},
         {"size", 10.0},
         {"material",
          {{"type", "diffuse_transmission"},
           {"reflectance", {0.1, 0.3, 0.5}},
           {"transmittance", {0.6, 0.4, 0.2}}}}}}},
      {"lights",
       {{{"type", "directional"}, {"direction", {0.0, light_side, 0.0}}, {"irradiance", 2.0}}}}};
}

TEST(MaterialRender, DiffuseTransmitterReflectsAndTransmitsLambertian) {
  const Rgb reflected = Rgb(0.1f, 0.3f, 0.5f) * (2.0f / kPi);
  const Rgb transmitted = Rgb(0.6f, 0.4f, 0.2f) * (2.0f / kPi);
  for (const char* integrator : kIntegrators) {
    for (const float side : {1.0f, -1.0f}) {
      const Film film = render_doc(sheet_scene(side), integrator, 4);
      const Rgb expected = side > 0 ? reflected : transmitted;
      for (const Rgb& m : film.mean) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(m[c], expected[c], 1e-5f) << integrator << " side " << side << " ch " << c;
        }
      }
    }
  }
}

// A unit sphere of `material` under a constant environment of radiance 1, seen from distance 4
// with the given field of view on a square image.
Film render_sphere_in_furnace(const json& material, double fov, int resolution,
                              const char* integrator, int spp) {
  const json doc = {{"camera",
                     {{"position", {0.0, 0.0, 4.0}},
                      {"look_at", {0.0, 0.0, 0.0}},
                      {"fov", fov},
                      {"resolution", {resolution, resolution}}}},
                    {"shapes",
                     {{{"type", "sphere"},
                       {"center", {0.0, 0.0, 0.0}},
                       {"radius", 1.0},
                       {"material", material}}}},
                    {"lights", {{{"type", "constant"}, {"radiance", 1.0}}}}};
  return render_doc(doc, integrator, spp);
}

// Seen through a 2 degree field of view from distance 4, every pixel sees the unit sphere
// within 4.1 degrees of its normal (cos > 0.997), where the lobe's albedo differs from its
// value at normal incidence by far less than the tolerance.
TEST(MaterialRender, RoughGoldSphereShowsTheLobeAlbedo) {
  const ComplexIor gold = *find_metal("gold");
  const ConductorParams p{gold.eta, gold.k, 0.3f};
  test::TestRng rng(51);
  test::MeanEstimator reference[3];
  for (int i = 0; i < 400'000; ++i) {
    const BsdfSample s = conductor_sample(p, Vec3(0, 0, 1), rng.uniform2());
    const Rgb w =
        s.valid ? conductor_fresnel(p, Vec3(0, 0, 1), s.wi) * (s.f * s.wi.z / s.pdf) : Rgb(0.0f);
    for (int c = 0; c < 3; ++c) reference[c].add(w[c]);
  }
  const json gold_material = {{"type", "conductor"}, {"metal", "gold"}, {"roughness", 0.3}};
  for (const char* integrator : kIntegrators) {
    const Film film = render_sphere_in_furnace(gold_material, 2.0, 8, integrator, 256);
    for (int c = 0; c < 3; ++c) {
      test::MeanEstimator pixels;
      double variance_of_mean = 0;
      for (size_t i = 0; i < film.mean.size(); ++i) {
        pixels.add(film.mean[i][c]);
        variance_of_mean += film.variance_of_mean[i][c];
      }
      const double se = std::sqrt(variance_of_mean) / film.mean.size();
      EXPECT_LT(
          test::z_score(pixels.mean(), se, reference[c].mean(), reference[c].standard_error()), 4.0)
          << integrator << " channel " << c << ": " << pixels.mean() << " vs "
          << reference[c].mean();
    }
  }
}

// A mirror that reflects everything (eta 0, k 1: F = 1 at every angle) sends each camera ray
// once into the environment with weight exactly 1: no integrator may see the sphere.
TEST(MaterialFurnace, WhiteMirrorIsInvisible) {
  const json mirror = {{"type", "conductor"}, {"eta", 0.0}, {"k", 1.0}};
  for (const char* integrator : kIntegrators) {
    const Film film = render_sphere_in_furnace(mirror, 35.0, 32, integrator, 4);
    for (const Rgb& m : film.mean) {
      EXPECT_NEAR(m.x, 1.0f, 1e-6f) << integrator;
      EXPECT_NEAR(m.y, 1.0f, 1e-6f) << integrator;
      EXPECT_NEAR(m.z, 1.0f, 1e-6f) << integrator;
    }
  }
}

// A closed sphere of a diffuse transmitter with R + T = 1 absorbs nothing: whatever happens
// to light inside, it leaves again, so the sphere renders exactly 1 (within the standard error
// of its coloured lobes' weights), for each integrator.
TEST(MaterialFurnace, LosslessDiffuseTransmitterIsInvisible) {
  const json sheet = {{"type", "diffuse_transmission"},
                      {"reflectance", {0.2, 0.5, 0.7}},
                      {"transmittance", {0.8, 0.5, 0.3}}};
  for (const char* integrator : kIntegrators) {
    SCOPED_TRACE(integrator);
    const Film film = render_sphere_in_furnace(sheet, 35.0, 32, integrator, 32);
    EXPECT_GT(test::region_mean(film, std::vector<bool>(film.mean.size(), true)).standard_error,
              0.0);
    test::expect_renders_to_one(film);
  }
}

}  // namespace
}  // namespace snee
