// Smooth shading (docs/method.md 4.9): the interpolation of vertex normals, the side rule that
// keeps light from passing a surface the wrong way, and whole renders: an icosphere whose
// normals are its vertex directions must render like the analytic sphere, where the same mesh
// shaded flat visibly does not (diffuse, with pt, snee and sla), and as the grid's translucent
// object (pt and snee); and a white furnace measures the energy the side rule removes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "kernels/stages/shading_normal.h"
#include "scene/vertex_normals.h"
#include "scheduler/render.h"
#include "tests/support/chi2.h"
#include "tests/support/icosphere.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

// --- interpolation ---

TEST(SmoothShading, BarycentricWeightsRebuildThePoint) {
  const Vec3 a(0.3f, -1.0f, 2.0f), b(1.5f, 0.2f, 1.0f), c(-0.4f, 0.9f, 0.5f);
  for (const Vec3 w : {Vec3(1, 0, 0), Vec3(0.2f, 0.3f, 0.5f), Vec3(0.6f, 0.4f, 0.0f)}) {
    const Vec3 p = a * w.x + b * w.y + c * w.z;
    const Vec3 got = barycentric_weights(a, b, c, p);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], w[i], 1e-5f) << i;
  }
  // A point a little outside the triangle interpolates between its corners only.
  const Vec3 outside = barycentric_weights(a, b, c, a * 1.01f + b * -0.01f);
  EXPECT_GE(outside.y, 0.0f);
  EXPECT_NEAR(outside.x + outside.y + outside.z, 1.0f, 1e-6f);
}

TriangleMesh one_triangle(Vec3 n0, Vec3 n1, Vec3 n2) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  m.normals = {normalize(n0), normalize(n1), normalize(n2)};
  return m;
}

TEST(SmoothShading, InterpolatedNormalIsTheCornersBlendTurnedToTheGeometricSide) {
  const Vec3 ng(0, 0, 1);
  const TriangleMesh m = one_triangle({-1, 0, 1}, {1, 0, 1}, {0, 0, 1});
  const Vec3 at_corner = interpolated_normal(m, 0, {0, 0, 0}, ng);
  EXPECT_NEAR(at_corner.x, -std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(at_corner.z, std::sqrt(0.5f), 1e-6f);
  // Midway between the first two corners the tilts cancel.
  const Vec3 mid = interpolated_normal(m, 0, {0.5f, 0, 0}, ng);
  EXPECT_NEAR(mid.x, 0.0f, 1e-6f);
  EXPECT_NEAR(mid.z, 1.0f, 1e-6f);
  // Normals that point inward (against the winding) are turned to the outward side.
  const TriangleMesh inward = one_triangle({0, 0, -1}, {0.2f, 0, -1}, {0, 0, -1});
  EXPECT_GT(dot(interpolated_normal(inward, 0, {0.2f, 0.2f, 0}, ng), ng), 0.9f);
  // A blend that vanishes falls back to the geometric normal.
  const TriangleMesh opposed = one_triangle({1, 0, 0}, {-1, 0, 0}, {1, 0, 0});
  EXPECT_EQ(interpolated_normal(opposed, 0, {0.5f, 0, 0}, ng), ng);
}

// --- the side rule ---

TEST(SmoothShading, DirectionsTheGeometryForbidsGetNothing) {
  const Vec3 ng(0, 0, 1);
  // A shading normal tilted 20 degrees toward +x.
  const float t = 20.0f * kPi / 180.0f;
  const Vec3 ns(std::sin(t), 0, std::cos(t));
  const Vec3 wo = normalize(Vec3(0.3f, 0.2f, 1.0f));  // above both
  // Above the shading horizon but below the triangle: a reflection that would leave through the
  // surface.
  const Vec3 below = normalize(Vec3(1.0f, 0.0f, -0.1f));
  ASSERT_GT(dot(below, ns), 0.0f);
  EXPECT_FALSE(shading_sides_agree(wo, below, ng, ns));
  // Below the shading horizon but above the triangle: a "transmission" that stays outside.
  const Vec3 above = normalize(Vec3(-1.0f, 0.0f, 0.1f));
  ASSERT_LT(dot(above, ns), 0.0f);
  EXPECT_FALSE(shading_sides_agree(wo, above, ng, ns));
  // Where the normals agree: reflection stays on wo's side, transmission crosses.
  EXPECT_TRUE(shading_sides_agree(wo, normalize(Vec3(-0.2f, 0.1f, 1.0f)), ng, ns));
  EXPECT_TRUE(shading_sides_agree(wo, normalize(Vec3(0.1f, 0.3f, -1.0f)), ng, ns));
  // A camera-side direction the two normals disagree on ends the path whatever wi is.
  EXPECT_FALSE(shading_sides_agree(below, wo, ng, ns));
  // Flat shading (ns = ng) never rejects a direction off the plane.
  EXPECT_TRUE(shading_sides_agree(wo, below, ng, ng));
}

// --- renders ---

enum class Object { kAnalytic, kSmooth, kFlat };

// sphere_scene's unit sphere of `material` (with the grid's medium inside a dielectric), or the
// icosphere in its place, lit by a directional light from the upper left and, with `sky`, a dim
// constant environment.
Scene test_scene(const Material& material, Object object, int resolution, bool sky) {
  const Medium grid_medium{"grid-medium", {4.0f, 5.0f, 6.0f}, {0.12f, 0.1f, 0.08f}, 0.0f, nullptr};
  Scene scene = test::sphere_scene(material, grid_medium, resolution);
  Shape& shape = scene.shapes[0];
  if (material.kind != MaterialKind::kDielectric) shape.interior_medium = -1;
  if (object != Object::kAnalytic) {
    shape.kind = ShapeKind::kMesh;
    shape.mesh = test::icosphere(3, object == Object::kSmooth);
    shape.smooth_shading = object == Object::kSmooth;
  }
  Light sun;
  sun.kind = LightKind::kDirectional;
  sun.direction = normalize(Vec3(-1.0f, 1.0f, 0.6f));
  sun.irradiance = Rgb(3.0f);
  scene.lights = {sun};
  if (sky) {
    Light env;
    env.kind = LightKind::kConstantEnv;
    env.radiance = Rgb(0.2f);
    scene.lights.push_back(env);
  }
  return scene;
}

Film render_with(const Scene& scene, const char* integrator, int spp) {
  RenderOptions options;
  options.spp = spp;
  options.seed = 11;
  options.integrator = integrator;
  return render(scene, options).film;
}

struct ChannelMean {
  double mean = 0, standard_error = 0;
};

ChannelMean channel_mean(const Film& film, const std::vector<bool>& mask, int c) {
  double sum = 0, var = 0;
  int n = 0;
  for (size_t i = 0; i < film.mean.size(); ++i) {
    if (!mask[i]) continue;
    sum += film.mean[i][c];
    var += film.variance_of_mean[i][c];
    ++n;
  }
  return {sum / n, std::sqrt(var) / n};
}

// The largest z-score between two renders over the blocks of the mask and the channels.
double largest_block_z(const Film& a, const Film& b, const std::vector<bool>& mask) {
  double largest = 0;
  for (const std::vector<bool>& block : test::blocks(a, mask, 4, 8)) {
    for (int c = 0; c < 3; ++c) {
      const ChannelMean ma = channel_mean(a, block, c), mb = channel_mean(b, block, c);
      largest =
          std::max(largest, test::z_score(ma.mean, ma.standard_error, mb.mean, mb.standard_error));
    }
  }
  return largest;
}

// Pixel by pixel: the chi-square survival of the sum of squared z-scores of channel c over the
// pixels of the mask where either render varies (a pixel both render without variance, e.g.
// unlit, says nothing).
double pixel_chi2_p(const Film& a, const Film& b, const std::vector<bool>& mask, int c) {
  double sum = 0;
  int dof = 0;
  for (size_t i = 0; i < a.mean.size(); ++i) {
    const double var = double{a.variance_of_mean[i][c]} + b.variance_of_mean[i][c];
    if (!mask[i] || !(var > 0)) continue;
    const double d = double{a.mean[i][c]} - b.mean[i][c];
    sum += d * d / var;
    ++dof;
  }
  return test::chi2_survival(sum, dof);
}

// Smooth matches the analytic sphere over the object, per channel and block by block. With
// `pixel_power`, also pixel by pixel, where flat shading's facets must show: a surface lit by a
// directional light varies only across each pixel's footprint, so the pixels' standard errors
// are small enough to see them. Under the light's refraction into a medium the facets blur
// away at any budget a test can pay (the measured numbers are printed and in the commit).
void expect_smooth_matches_analytic(const Material& material, const char* integrator,
                                    int resolution, int spp, bool sky, bool pixel_power) {
  SCOPED_TRACE(integrator);
  const Scene analytic_scene = test_scene(material, Object::kAnalytic, resolution, sky);
  const Film analytic = render_with(analytic_scene, integrator, spp);
  const Film smooth =
      render_with(test_scene(material, Object::kSmooth, resolution, sky), integrator, spp);
  const Film flat =
      render_with(test_scene(material, Object::kFlat, resolution, sky), integrator, spp);
  // Inside the icosphere's silhouette too, which lies within 0.2% of the radius of the sphere's.
  const std::vector<bool> mask = test::sphere_mask(analytic_scene, {0, 0, 0}, 0.97f);
  for (int c = 0; c < 3; ++c) {
    const ChannelMean a = channel_mean(analytic, mask, c), s = channel_mean(smooth, mask, c),
                      f = channel_mean(flat, mask, c);
    const double z_smooth = test::z_score(s.mean, s.standard_error, a.mean, a.standard_error);
    const double z_flat = test::z_score(f.mean, f.standard_error, a.mean, a.standard_error);
    std::printf(
        "%s channel %d: analytic %.5f +- %.5f, smooth %.5f +- %.5f (z %.2f), flat %.5f +- "
        "%.5f (z %.2f)\n",
        integrator, c, a.mean, a.standard_error, s.mean, s.standard_error, z_smooth, f.mean,
        f.standard_error, z_flat);
    EXPECT_LT(z_smooth, 4.0) << "channel " << c;
  }
  // Some 30 blocks and 3 channels: 5 standard errors keep false alarms below 1e-4.
  const double blocks_smooth = largest_block_z(smooth, analytic, mask);
  const double blocks_flat = largest_block_z(flat, analytic, mask);
  std::printf("%s largest 4x4-block z: smooth %.2f, flat %.2f\n", integrator, blocks_smooth,
              blocks_flat);
  EXPECT_LT(blocks_smooth, 5.0);
  if (!pixel_power) return;
  for (int c = 0; c < 3; ++c) {
    const double p_smooth = pixel_chi2_p(smooth, analytic, mask, c);
    const double p_flat = pixel_chi2_p(flat, analytic, mask, c);
    std::printf("%s channel %d pixel chi-square p: smooth %.3g, flat %.3g\n", integrator, c,
                p_smooth, p_flat);
    EXPECT_GT(p_smooth, 1e-4) << "channel " << c;
    EXPECT_LT(p_flat, 1e-20) << "channel " << c;
  }
}

TEST(SmoothShading, DiffuseIcosphereRendersLikeTheSphere) {
  Material white;
  white.kind = MaterialKind::kDiffuse;
  white.albedo = Rgb(0.8f, 0.6f, 0.4f);
  for (const char* integrator : {"pt", "snee", "sla"})
    expect_smooth_matches_analytic(white, integrator, 32, 8, false, true);
}

TEST(SmoothShading, TranslucentIcosphereRendersLikeTheSphere) {
  Material interface;
  interface.kind = MaterialKind::kDielectric;
  interface.ior = 1.5f;
  interface.roughness = 0.2f;
  for (const char* integrator : {"pt", "snee"}) {
    expect_smooth_matches_analytic(interface, integrator, 24, 256, true, false);
  }
}

// A closed white object in a white furnace must look 1 everywhere. With shading normals the
// side rule ends the rare paths whose directions the two normals disagree on, so the smooth
// icosphere may only lose energy, never gain it; the loss is measured and bounded (docs/method.md
// 4.9).
void expect_furnace_loss_bounded(const Material& material, const Medium& medium,
                                 const char* integrator, double bound) {
  SCOPED_TRACE(integrator);
  Scene scene = test::sphere_scene(material, medium, 16);
  Shape& shape = scene.shapes[0];
  if (material.kind != MaterialKind::kDielectric) shape.interior_medium = -1;
  shape.kind = ShapeKind::kMesh;
  shape.mesh = test::icosphere(3, true);
  shape.smooth_shading = true;
  Light sky;
  sky.kind = LightKind::kConstantEnv;
  sky.radiance = Rgb(1.0f);
  scene.lights = {sky};
  const Film film = render_with(scene, integrator, 64);
  const test::RegionStats object =
      test::region_mean(film, test::sphere_mask(scene, {0, 0, 0}, 0.97f));
  std::printf("%s furnace over the object: %.5f +- %.5f (loss %.3f%%)\n", integrator, object.mean,
              object.standard_error, 100.0 * (1.0 - object.mean));
  EXPECT_LT(object.mean, 1.0 + 4.0 * object.standard_error);
  EXPECT_GT(object.mean, 1.0 - bound - 4.0 * object.standard_error);
}

TEST(SmoothShading, FurnaceDiffuseLosesLittleEnergy) {
  Material white;
  white.kind = MaterialKind::kDiffuse;
  white.albedo = Rgb(1.0f);
  for (const char* integrator : {"pt", "snee"}) {
    expect_furnace_loss_bounded(white, Medium{}, integrator, 0.01);
  }
}

TEST(SmoothShading, FurnaceDielectricLosesLittleEnergy) {
  Material glass;
  glass.kind = MaterialKind::kDielectric;
  glass.ior = 1.5f;
  const Medium white_medium{"white", Rgb(2.0f), Rgb(0.0f), 0.0f, nullptr};
  for (const char* integrator : {"pt", "snee"}) {
    expect_furnace_loss_bounded(glass, white_medium, integrator, 0.01);
  }
}

}  // namespace
}  // namespace snee
