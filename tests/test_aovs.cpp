// The denoiser AOVs (kernels/stages/first_hit_aovs.h) on scenes where each is known analytically: a
// diffuse plane facing the camera (albedo and normal exact in every pixel, depth between the
// extremes of its pixel's footprint and, over the image, the footprint integral), a diffuse
// sphere's normal field, a smooth dielectric sphere over a diffuse floor (the albedo through the
// specular chain is the floor's times the Fresnel-weighted chance of reaching it) and a dense
// medium behind an index-matched smooth boundary (its single-scattering albedo). Recording AOVs
// must leave the beauty image bitwise unchanged, and the AOVs themselves are bitwise the same
// for every schedule and thread count.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/physics/bsdf/fresnel.h"
#include "scene/aov_selection.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

constexpr AovSelection kAllAovs{true, true, true};

// Camera on +z at `distance` from the origin looking down -z, so that a pixel's direction is
// forward + right x + up y with x, y the film coordinates scaled by the field of view.
Scene facing_camera_scene(float distance, float fov_degrees, int resolution) {
  Scene scene;
  scene.name = "aov-test";
  scene.camera.position = {0, 0, distance};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 1, 0};
  scene.camera.fov_degrees = fov_degrees;
  scene.camera.width = scene.camera.height = resolution;
  return scene;
}

// A square of half-size h in the plane z = z0, facing +z, with material `material`.
Shape square(float z0, float h, int material) {
  Shape s;
  s.name = "square";
  s.mesh.positions = {{-h, -h, z0}, {h, -h, z0}, {h, h, z0}, {-h, h, z0}};
  s.mesh.indices = {0, 1, 2, 0, 2, 3};
  s.material = material;
  s.closed = false;
  return s;
}

Material diffuse(Rgb albedo) {
  Material m;
  m.name = "diffuse";
  m.kind = MaterialKind::kDiffuse;
  m.albedo = albedo;
  return m;
}

// Tangent-plane film coordinates of the pixel corner (px, py): the camera ray through it is
// (x, y, -1) before normalising (the scene's camera looks down -z with y up).
struct FilmPoint {
  double x, y;
};
FilmPoint film_point(const Scene& scene, double px, double py) {
  const Camera& c = scene.camera;
  const double tan_half = std::tan(0.5 * c.fov_degrees * kPi / 180.0);
  const double aspect = static_cast<double>(c.width) / c.height;
  return {(2.0 * px / c.width - 1.0) * tan_half * aspect, (1.0 - 2.0 * py / c.height) * tan_half};
}

size_t index(const Scene& scene, int x, int y) {
  return static_cast<size_t>(y) * static_cast<size_t>(scene.camera.width) + static_cast<size_t>(x);
}

RenderOptions aov_options(int spp) {
  RenderOptions options;
  options.spp = spp;
  options.seed = 5;
  options.threads = 2;
  options.aovs = kAllAovs;
  return options;
}

TEST(Aovs, DiffusePlaneFacingTheCameraIsExactInEveryPixel) {
  const float distance = 3.0f;
  Scene scene = facing_camera_scene(distance, 40.0f, 24);
  const Rgb albedo{0.2f, 0.5f, 0.8f};
  scene.materials.push_back(diffuse(albedo));
  scene.shapes.push_back(square(0.0f, 10.0f, 0));
  const int spp = 32;
  const Film film = render(scene, aov_options(spp)).film;
  ASSERT_EQ(film.albedo.size(), film.mean.size());
  ASSERT_EQ(film.normal.size(), film.mean.size());
  ASSERT_EQ(film.depth.size(), film.mean.size());
  double depth_sum = 0;
  for (int y = 0; y < scene.camera.height; ++y) {
    for (int x = 0; x < scene.camera.width; ++x) {
      const size_t i = index(scene, x, y);
      // Every sample sees the same albedo and normal: their mean is the value itself.
      EXPECT_EQ(film.albedo[i].x, albedo.x);
      EXPECT_EQ(film.albedo[i].y, albedo.y);
      EXPECT_EQ(film.albedo[i].z, albedo.z);
      EXPECT_NEAR(film.normal[i].x, 0.0f, 1e-6f);
      EXPECT_NEAR(film.normal[i].y, 0.0f, 1e-6f);
      EXPECT_NEAR(film.normal[i].z, 1.0f, 1e-6f);
      // Depth along the ray through film point (u, v) is distance * sqrt(1 + u^2 + v^2): at
      // least at the footprint's point nearest the axis, at most at its farthest corner.
      const FilmPoint a = film_point(scene, x, y + 1), b = film_point(scene, x + 1, y);
      const double near_u = std::clamp(0.0, a.x, b.x), near_v = std::clamp(0.0, a.y, b.y);
      const double far_u = std::max(std::fabs(a.x), std::fabs(b.x));
      const double far_v = std::max(std::fabs(a.y), std::fabs(b.y));
      const double lo = distance * std::sqrt(1 + near_u * near_u + near_v * near_v);
      const double hi = distance * std::sqrt(1 + far_u * far_u + far_v * far_v);
      EXPECT_GE(film.depth[i], lo * (1 - 1e-5)) << x << "," << y;
      EXPECT_LE(film.depth[i], hi * (1 + 1e-5)) << x << "," << y;
      depth_sum += film.depth[i];
    }
  }
  // Over the whole image the mean depth estimates the integral of the depth over the film
  // (midpoint rule on a fine grid, error far below the tolerance). Its standard error comes
  // from the depth's spread over a pixel (at most hi - lo, a bound on the per-sample deviation).
  const FilmPoint corner = film_point(scene, 0, 0);
  const int grid = 2000;
  double integral = 0;
  for (int j = 0; j < grid; ++j) {
    for (int k = 0; k < grid; ++k) {
      const double u = corner.x * (1 - 2 * (k + 0.5) / grid);
      const double v = corner.y * (1 - 2 * (j + 0.5) / grid);
      integral += distance * std::sqrt(1 + u * u + v * v);
    }
  }
  integral /= static_cast<double>(grid) * grid;
  const double pixels = static_cast<double>(film.depth.size());
  const double spread = distance * std::sqrt(2.0) * 2 * std::fabs(corner.x) / scene.camera.width;
  const double standard_error = spread / std::sqrt(pixels * spp);
  EXPECT_NEAR(depth_sum / pixels, integral, 5 * standard_error + 1e-5 * integral);
}

// A rough conductor's albedo is its normal-incidence reflectance, a diffuse transmitter's its
// reflectance plus transmittance: the same in every sample, so exact in every pixel.
TEST(Aovs, ConductorAndDiffuseTransmitterAlbedos) {
  Material gold;
  gold.kind = MaterialKind::kConductor;
  gold.conductor_eta = {0.143f, 0.375f, 1.442f};
  gold.conductor_k = {3.983f, 2.386f, 1.603f};
  gold.roughness = 0.3f;
  Material sheet;
  sheet.kind = MaterialKind::kDiffuseTransmission;
  sheet.albedo = {0.1f, 0.2f, 0.3f};
  sheet.transmittance = {0.5f, 0.25f, 0.125f};
  const Rgb f0 = fresnel_conductor(1.0f, gold.conductor_eta, gold.conductor_k);
  for (const auto& [material, expected] :
       {std::pair{gold, f0}, std::pair{sheet, sheet.albedo + sheet.transmittance}}) {
    Scene scene = facing_camera_scene(3.0f, 40.0f, 8);
    scene.materials.push_back(material);
    scene.shapes.push_back(square(0.0f, 10.0f, 0));
    const Film film = render(scene, aov_options(4)).film;
    ASSERT_EQ(film.albedo.size(), film.mean.size());
    for (const Rgb& a : film.albedo) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], expected[c]) << c;
    }
  }
}

TEST(Aovs, DiffuseSphereShowsItsNormalField) {
  Scene scene = facing_camera_scene(4.0f, 35.0f, 32);
  scene.materials.push_back(diffuse(Rgb(0.7f)));
  Shape sphere;
  sphere.name = "sphere";
  sphere.kind = ShapeKind::kSphere;
  sphere.material = 0;
  scene.shapes.push_back(sphere);
  const Film film = render(scene, aov_options(16)).film;
  const std::vector<bool> inside = test::sphere_mask(scene);
  const Vec3 camera = scene.camera.position;
  // The unit sphere's normal where the ray through film point (u, v) meets it.
  const auto normal_at = [&](double px, double py) {
    const FilmPoint f = film_point(scene, px, py);
    const Vec3 d = normalize(Vec3(static_cast<float>(f.x), static_cast<float>(f.y), -1.0f));
    const float b = dot(camera, d);
    const float t = -b - std::sqrt(b * b - (dot(camera, camera) - 1.0f));
    return camera + d * t;
  };
  int tested = 0;
  for (int y = 0; y < scene.camera.height; ++y) {
    for (int x = 0; x < scene.camera.width; ++x) {
      const size_t i = index(scene, x, y);
      if (!inside[i]) continue;
      ++tested;
      EXPECT_EQ(film.albedo[i].x, 0.7f);
      // The mean of unit normals over the footprint lies in the cone of those normals around
      // the centre's: within its widest corner angle, and not shorter than that cone allows.
      const Vec3 centre = normal_at(x + 0.5, y + 0.5);
      float widest = 0;
      for (const auto& [cx, cy] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}}) {
        widest =
            std::max(widest, std::acos(std::min(1.0f, dot(centre, normal_at(x + cx, y + cy)))));
      }
      const Vec3 n = film.normal[i];
      EXPECT_LE(length(n), 1.0f + 1e-5f);
      EXPECT_GE(length(n), std::cos(widest) - 1e-4f);
      EXPECT_LE(std::acos(std::min(1.0f, dot(normalize(n), centre))), widest * 1.01f + 1e-4f)
          << x << "," << y;
      // The camera sees the front: the normal faces it.
      EXPECT_GT(n.z, 0.0f);
    }
  }
  EXPECT_GT(tested, 200);
  // A pixel that misses the sphere escapes: no hit, zero AOVs.
  EXPECT_EQ(film.albedo[index(scene, 0, 0)].x, 0.0f);
  EXPECT_EQ(film.normal[index(scene, 0, 0)].z, 0.0f);
  EXPECT_EQ(film.depth[index(scene, 0, 0)], 0.0f);
}

// Unit sphere of a smooth dielectric (index `ior`), optionally filled with `medium`, over a
// diffuse floor of albedo `floor_albedo` facing the camera at z = -2; the camera looks down -z
// through a narrow view so that the centre pixel's rays all meet the sphere almost head on.
Scene glass_over_floor(float ior, Rgb floor_albedo, const Medium* medium) {
  Scene scene = facing_camera_scene(4.0f, 4.0f, 9);
  Material glass;
  glass.name = "glass";
  glass.kind = MaterialKind::kDielectric;
  glass.ior = ior;
  scene.materials.push_back(glass);
  scene.materials.push_back(diffuse(floor_albedo));
  Shape sphere;
  sphere.name = "sphere";
  sphere.kind = ShapeKind::kSphere;
  sphere.material = 0;
  if (medium) {
    scene.media.push_back(*medium);
    sphere.interior_medium = 0;
  }
  scene.shapes.push_back(sphere);
  scene.shapes.push_back(square(-2.0f, 50.0f, 1));
  return scene;
}

TEST(Aovs, AlbedoThroughASmoothDielectricIsTheFresnelWeightedFloorAlbedo) {
  const float ior = 1.5f;
  const Rgb floor{0.25f, 0.5f, 0.75f};
  const Scene scene = glass_over_floor(ior, floor, nullptr);
  const int spp = 8192;
  const Film film = render(scene, aov_options(spp)).film;
  const size_t centre = index(scene, 4, 4);
  // Head on, each crossing reflects with R = ((n - 1) / (n + 1))^2. A path reaches the floor
  // when it enters, bounces inside 2k times and leaves at the back: sum_k T^2 R^2k; a path that
  // reflects off the front, or leaves through it, escapes toward the camera (albedo 0).
  const double r = std::pow((ior - 1.0) / (ior + 1.0), 2.0), t = 1 - r;
  const double p_floor = t * t / (1 - r * r);
  // Each sample's albedo is the floor's or 0: a Bernoulli(p_floor) draw scaled by it.
  const double se = std::sqrt(p_floor * (1 - p_floor) / spp);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(film.albedo[centre][c], floor[c] * p_floor, 5 * se * floor[c]) << c;
  // The same samples' normal is the floor's, +z, or 0.
  EXPECT_NEAR(film.normal[centre].z, p_floor, 5 * se);
  // Seen through the glass is not seeing the glass: never the sphere's albedo of 1.
  EXPECT_LT(film.albedo[centre].x, floor.x);
}

TEST(Aovs, MediumInteractionHasTheSingleScatteringAlbedo) {
  Medium dense;
  dense.name = "dense";
  dense.sigma_s = {20.0f, 30.0f, 40.0f};
  dense.sigma_a = {5.0f, 10.0f, 20.0f};
  // Index-matched but smooth: a specular boundary the chain passes without reflecting.
  const Scene scene = glass_over_floor(1.0f, Rgb(0.5f), &dense);
  const Film film = render(scene, aov_options(64)).film;
  const Rgb sigma_t = dense.sigma_t();
  // Every pixel of this narrow view sees chords through the sphere over 1.8 long: no flight
  // crosses one unscattered (transmittance below e^-45 in every channel).
  for (size_t i = 0; i < film.albedo.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(film.albedo[i][c], dense.sigma_s[c] / sigma_t[c]);
    // Facing back along the camera ray: nearly +z in this narrow view.
    EXPECT_GT(film.normal[i].z, 0.999f);
    // The vertex lies inside the sphere: past its front (at 3) and before its back (at 5).
    EXPECT_GT(film.depth[i], 3.0f);
    EXPECT_LT(film.depth[i], 5.0f);
  }
}

// A translucent sphere with a light: every integrator has work at every stage.
Scene lit_translucent_scene() {
  Medium milk;
  milk.name = "milk";
  milk.sigma_s = {2.0f, 3.0f, 4.0f};
  milk.sigma_a = {0.2f, 0.1f, 0.05f};
  milk.g = 0.3f;
  Scene scene = glass_over_floor(1.4f, Rgb(0.6f), &milk);
  scene.camera.fov_degrees = 40.0f;
  scene.camera.width = scene.camera.height = 16;
  Light env;
  env.kind = LightKind::kConstantEnv;
  env.radiance = Rgb(0.3f, 0.4f, 0.5f);
  scene.lights.push_back(env);
  Light sun;
  sun.kind = LightKind::kDirectional;
  sun.direction = normalize(Vec3(0.3f, 1.0f, 0.6f));
  sun.radiance = Rgb(3.0f);
  scene.lights.push_back(sun);
  return scene;
}

bool same_floats(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
bool same_vectors(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

// The AOVs are as deterministic as the beauty: wherever two schedules or thread counts give
// the same beauty bits, they give the same AOV bits. (The megakernel's beauty differs from the
// queued schedules' in the last bit on this scene before any AOV exists; that is compared
// only against its own plain render.)
TEST(Aovs, BeautyIsUnchangedAndAovsAreAsDeterministicAsIt) {
  const Scene scene = lit_translucent_scene();
  for (const char* integrator : {"pt", "sla", "snee"}) {
    RenderOptions plain;
    plain.spp = 8;
    plain.seed = 3;
    plain.threads = 1;
    plain.integrator = integrator;
    const Film reference = render(scene, plain).film;
    EXPECT_TRUE(reference.albedo.empty() && reference.normal.empty() && reference.depth.empty());
    RenderOptions with_aovs = plain;
    with_aovs.aovs = kAllAovs;
    const Film reference_aovs = render(scene, with_aovs).film;
    int compared = 0;
    for (const char* schedule : {"local", "megakernel", "global"}) {
      for (const int threads : {1, 2}) {
        RenderOptions o = plain;
        o.schedule = schedule;
        o.threads = threads;
        const Film beauty = render(scene, o).film;
        o.aovs = kAllAovs;
        const Film film = render(scene, o).film;
        const std::string where =
            std::string(integrator) + " " + schedule + " " + std::to_string(threads) + " threads";
        EXPECT_TRUE(test::bitwise_identical(film, beauty)) << where;
        if (!test::bitwise_identical(beauty, reference)) continue;
        ++compared;
        EXPECT_TRUE(same_vectors(film.albedo, reference_aovs.albedo)) << where;
        EXPECT_TRUE(same_vectors(film.normal, reference_aovs.normal)) << where;
        EXPECT_TRUE(same_floats(film.depth, reference_aovs.depth)) << where;
      }
    }
    // local and global on one and two threads at least.
    EXPECT_GE(compared, 4) << integrator;
  }
}

TEST(Aovs, OnlyTheChosenLayersAreKept) {
  const Scene scene = lit_translucent_scene();
  RenderOptions o;
  o.spp = 2;
  o.aovs.normal = true;
  const Film film = render(scene, o).film;
  EXPECT_TRUE(film.albedo.empty());
  EXPECT_EQ(film.normal.size(), film.mean.size());
  EXPECT_TRUE(film.depth.empty());
}

}  // namespace
}  // namespace snee
