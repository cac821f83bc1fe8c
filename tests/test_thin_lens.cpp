// The thin-lens camera: the concentric disk map is uniform, a square emitter in the focal plane
// images as sharply as through a pinhole, one off the focal plane spreads by the blur disk of
// the thin-lens formula, fov_axis fixes the angle along its edge at any resolution, a zero
// aperture renders the pinhole's bits, and the lens's images do not depend on the schedule.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernels/physics/camera.h"
#include "kernels/physics/sampling.h"
#include "scene/camera_frame.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "tests/support/render_helpers.h"
#include "tests/support/statistics.h"

namespace snee {
namespace {

constexpr int kSize = 64;
constexpr float kFov = 20.0f;

// Film units (tangent of the angle off the axis) per pixel at kSize x kSize and kFov.
double pixel_tan() {
  return 2.0 * std::tan(0.5 * kFov * kPi / 180.0) / kSize;
}

// A camera at the origin looking down -z at an emissive square of half-size `half` at depth
// `depth`, facing it, centred on the axis; nothing else in the scene.
Scene square_scene(float depth, float half, float aperture, float focus) {
  Scene scene;
  scene.name = "thin-lens";
  Camera& c = scene.camera;
  c.position = {0, 0, 0};
  c.look_at = {0, 0, -1};
  c.up = {0, 1, 0};
  c.fov_degrees = kFov;
  c.width = c.height = kSize;
  c.aperture_radius = aperture;
  c.focus_distance = focus;
  Material black;
  black.albedo = Rgb(0.0f);
  scene.materials = {black};
  Shape s;
  s.kind = ShapeKind::kMesh;
  s.mesh.positions = {
      {-half, -half, -depth}, {half, -half, -depth}, {half, half, -depth}, {-half, half, -depth}};
  s.mesh.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from the camera
  s.closed = false;
  s.material = 0;
  s.emission = Rgb(1.0f);
  scene.shapes = {s};
  Light light;
  light.kind = LightKind::kArea;
  light.shape = 0;
  scene.lights.push_back(light);
  return scene;
}

RenderOptions options(int spp) {
  RenderOptions o;
  o.spp = spp;
  o.seed = 3;
  o.integrator = "pt";
  o.max_depth = 0;  // the emitter seen by camera rays is all there is
  return o;
}

// The energy-weighted mean squared pixel distance from the image centre, with its standard
// error from the per-pixel variances (a ratio estimator, linearised).
struct Moment {
  double value = 0, standard_error = 0;
};

Moment second_moment(const Film& film) {
  double energy = 0, weighted = 0;
  auto r2 = [](int x, int y) {
    const double dx = x + 0.5 - kSize / 2.0, dy = y + 0.5 - kSize / 2.0;
    return dx * dx + dy * dy;
  };
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double v = average(film.mean[static_cast<size_t>(y * kSize + x)]);
      energy += v;
      weighted += v * r2(x, y);
    }
  }
  Moment m;
  m.value = weighted / energy;
  double var = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      // Every channel carries the same emission, so one channel's variance is the pixel's.
      const double v = film.variance_of_mean[static_cast<size_t>(y * kSize + x)].x;
      var += v * std::pow(r2(x, y) - m.value, 2);
    }
  }
  m.standard_error = std::sqrt(var) / energy;
  return m;
}

TEST(ThinLens, ConcentricDiskIsUniformAndInside) {
  constexpr int kRings = 8, kSectors = 16, kPerCell = 500;
  std::vector<double> counts(kRings * kSectors, 0.0);
  std::mt19937 engine(11);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < kRings * kSectors * kPerCell; ++i) {
    const Vec2 d = sample_concentric_disk({uniform(engine), uniform(engine)});
    const double r2 = double{d.x} * d.x + double{d.y} * d.y;
    ASSERT_LE(r2, 1.0 + 1e-6) << d.x << ", " << d.y;
    // Rings of equal area: r^2 in [k / kRings, (k + 1) / kRings).
    const int ring = std::min(kRings - 1, static_cast<int>(r2 * kRings));
    const double phi = std::atan2(d.y, d.x) + kPi;
    const int sector = std::min(kSectors - 1, static_cast<int>(phi / (2 * kPi) * kSectors));
    counts[ring * kSectors + sector] += 1;
  }
  double chi2 = 0;
  for (const double c : counts) chi2 += (c - kPerCell) * (c - kPerCell) / kPerCell;
  const double p = test::chi2_survival(chi2, kRings * kSectors - 1);
  EXPECT_GT(p, 1e-3) << "chi2 " << chi2;
  // The centre of the square is the centre of the disk; the same numbers give the same point.
  const Vec2 centre = sample_concentric_disk({0.5f, 0.5f});
  EXPECT_EQ(centre.x, 0.0f);
  EXPECT_EQ(centre.y, 0.0f);
  const Vec2 a = sample_concentric_disk({0.3f, 0.9f}), b = sample_concentric_disk({0.3f, 0.9f});
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
}

// In the focal plane every lens point sees the film position's point of the pinhole, so the
// lens image is the pinhole image: the same footprint, and the same values up to rays that
// graze the square's edges by float rounding.
TEST(ThinLens, FocalPlaneStaysSharp) {
  const float depth = 3.0f;
  const float half = static_cast<float>(3 * pixel_tan() * depth);  // 6 pixels wide
  const Film pinhole = render(square_scene(depth, half, 0.0f, 0.0f), options(16)).film;
  const Film lens = render(square_scene(depth, half, 0.2f, depth), options(16)).film;
  double energy = 0, difference = 0;
  int lit = 0;
  for (size_t i = 0; i < pinhole.mean.size(); ++i) {
    const double p = average(pinhole.mean[i]), l = average(lens.mean[i]);
    energy += p;
    difference += std::fabs(p - l);
    EXPECT_EQ(p > 0, l > 0) << "pixel " << i % kSize << ", " << i / kSize;
    lit += p > 0;
  }
  EXPECT_GE(lit, 36);
  EXPECT_LE(difference, 1e-3 * energy) << difference << " of " << energy;
}

// A square at depth d with focus distance f spreads into itself convolved with a uniform disk of
// radius A |d - f| / d on the focal plane, c = A |d - f| / d / (f * pixel_tan) pixels. Under a
// convolution second moments add, and a uniform disk's E[r^2] is c^2 / 2.
TEST(ThinLens, OutOfFocusBlurMatchesThinLensFormula) {
  const float depth = 4.0f, focus = 2.0f, aperture = 0.18f;
  const double c = aperture * std::fabs(depth - focus) / depth / (focus * pixel_tan());
  ASSERT_GT(c, 7.0);
  // Edges on pixel boundaries, 4 pixels wide, so the pinhole image is the square exactly.
  const float half = static_cast<float>(2 * pixel_tan() * depth);
  const Film pinhole = render(square_scene(depth, half, 0.0f, 0.0f), options(64)).film;
  const Film blurred = render(square_scene(depth, half, aperture, focus), options(256)).film;
  const Moment p = second_moment(pinhole), b = second_moment(blurred);
  const double measured = b.value - p.value;
  const double se = std::hypot(p.standard_error, b.standard_error);
  const double expected = c * c / 2;
  EXPECT_NEAR(measured, expected, 5 * se)
      << "E[r^2] " << measured << " +- " << se << ", thin lens " << expected;
  std::printf("blur E[r^2] %.3f +- %.3f px^2, thin lens %.3f (c = %.3f px)\n", measured, se,
              expected, c);
  // Nothing lands beyond the disk around the square (its half-diagonal, half a pixel's).
  const double reach = c + 2 * std::sqrt(2.0) + std::sqrt(0.5) + 1e-3;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double dx = x + 0.5 - kSize / 2.0, dy = y + 0.5 - kSize / 2.0;
      if (std::hypot(dx, dy) > reach) {
        EXPECT_EQ(average(blurred.mean[static_cast<size_t>(y * kSize + x)]), 0.0f)
            << x << ", " << y;
      }
    }
  }
}

// The angle from the axis to the image's left edge (horizontal), top edge (vertical) or corner
// (diagonal), through the renderer's own ray function.
double edge_angle_degrees(const Camera& c) {
  const FilmCamera film{camera_frame(c), static_cast<uint32_t>(c.width),
                        1.0f / static_cast<float>(c.width), 1.0f / static_cast<float>(c.height)};
  const float w = static_cast<float>(c.width), h = static_cast<float>(c.height);
  const float px = c.fov_axis == FovAxis::kVertical ? 0.5f * w : 0.0f;
  const float py = c.fov_axis == FovAxis::kHorizontal ? 0.5f * h : 0.0f;
  const Vec3 d = camera_direction(film, px, py, 0.0f, 0.0f);
  return std::acos(std::clamp(dot(d, film.frame.forward), -1.0f, 1.0f)) * 180.0 / kPi;
}

TEST(ThinLens, FovAxisKeepsItsAngleAtAnyResolution) {
  for (const FovAxis axis : {FovAxis::kVertical, FovAxis::kHorizontal, FovAxis::kDiagonal}) {
    for (const auto& [w, h] : {std::pair{64, 32}, std::pair{32, 64}, std::pair{17, 17}}) {
      Camera c;
      c.fov_degrees = 60;
      c.fov_axis = axis;
      c.width = w;
      c.height = h;
      EXPECT_NEAR(edge_angle_degrees(c), 30.0, 1e-4)
          << "axis " << static_cast<int>(axis) << " at " << w << "x" << h;
      const HalfExtents e = image_half_extents(c);
      EXPECT_NEAR(e.x / e.y, static_cast<double>(w) / h, 1e-6);
    }
  }
}

// The same scene document with and without "aperture_radius": 0 (and a focus distance, which
// a pinhole ignores) renders the same bits: a pinhole draws no lens numbers.
TEST(ThinLens, ZeroApertureIsThePinholeBitForBit) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "camera": {"position": [0, 0.3, 4], "look_at": [0, 0, 0], "fov": 35, "resolution": [24, 16]},
    "render": {"spp": 8, "max_depth": 4},
    "materials": [{"name": "white", "type": "diffuse", "albedo": 0.7}],
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}],
    "lights": [{"type": "constant", "radiance": 1}]
  })");
  const LoadedScene plain = load_scene_json(doc, "plain", "/");
  doc["camera"]["aperture_radius"] = 0;
  doc["camera"]["focus_distance"] = 7;
  const LoadedScene zero = load_scene_json(doc, "zero", "/");
  EXPECT_EQ(plain.canonical["camera"].contains("aperture_radius"), false);
  RenderOptions o = options(8);
  o.max_depth = 4;
  EXPECT_TRUE(test::bitwise_identical(render(plain.scene, o).film, render(zero.scene, o).film));
}

// Lens rays come from the one batched generation kernel every schedule runs.
TEST(ThinLens, EveryScheduleGivesIdenticalBytes) {
  const Scene scene = square_scene(4.0f, 0.05f, 0.18f, 2.0f);
  RenderOptions base = options(4);
  base.tile_size = 8;
  base.samples_per_unit = 2;
  base.queue_capacity = 64;
  base.threads = 1;
  const Film reference = render(scene, base).film;
  for (const char* schedule : {"megakernel", "local", "global"}) {
    for (const int threads : {1, 2}) {
      RenderOptions o = base;
      o.schedule = schedule;
      o.threads = threads;
      EXPECT_TRUE(test::bitwise_identical(reference, render(scene, o).film))
          << schedule << " with " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace snee
