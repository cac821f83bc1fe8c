#include "tests/support/render_helpers.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "tests/support/statistics.h"

namespace snee::test {

bool bitwise_identical(const Film& a, const Film& b) {
  return a.mean.size() == b.mean.size() && a.variance_of_mean.size() == b.variance_of_mean.size() &&
         std::memcmp(a.mean.data(), b.mean.data(), a.mean.size() * sizeof(Rgb)) == 0 &&
         std::memcmp(a.variance_of_mean.data(), b.variance_of_mean.data(),
                     a.variance_of_mean.size() * sizeof(Rgb)) == 0;
}

Scene sphere_scene(const Material& material, const Medium& medium, int resolution) {
  Scene scene;
  scene.name = "test-sphere";
  scene.camera.position = {0, 0, 4};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 1, 0};
  scene.camera.fov_degrees = 35;
  scene.camera.width = scene.camera.height = resolution;
  scene.materials.push_back(material);
  scene.media.push_back(medium);
  Shape sphere;
  sphere.name = "sphere";
  sphere.kind = ShapeKind::kSphere;
  sphere.center = {0, 0, 0};
  sphere.radius = 1;
  sphere.material = 0;
  sphere.interior_medium = 0;
  scene.shapes.push_back(sphere);
  return scene;
}

RegionStats region_mean(const Film& film, const std::vector<bool>& mask) {
  double sum = 0, var = 0;
  int n = 0;
  for (size_t i = 0; i < film.mean.size(); ++i) {
    if (!mask[i]) continue;
    sum += average(film.mean[i]);
    // Channels of one pixel are correlated; the variance of their average is bounded by the
    // average of their standard deviations squared, which is what is used (conservative).
    const Rgb v = film.variance_of_mean[i];
    const double sd = (std::sqrt(v.x) + std::sqrt(v.y) + std::sqrt(v.z)) / 3.0;
    var += sd * sd;
    ++n;
  }
  RegionStats r;
  r.pixels = n;
  if (n == 0) return r;
  r.mean = sum / n;
  r.standard_error = std::sqrt(var) / n;
  return r;
}

std::vector<bool> sphere_mask(const Scene& scene, Vec3 center, float radius) {
  const Camera& c = scene.camera;
  const Vec3 forward = normalize(c.look_at - c.position);
  const Vec3 right = normalize(cross(forward, c.up));
  const Vec3 up = cross(right, forward);
  const float tan_half = std::tan(0.5f * c.fov_degrees * kPi / 180.0f);
  const float aspect = static_cast<float>(c.width) / static_cast<float>(c.height);
  auto hits = [&](float px, float py) {
    const float x = (2.0f * px / c.width - 1.0f) * tan_half * aspect;
    const float y = (1.0f - 2.0f * py / c.height) * tan_half;
    const Vec3 d = normalize(forward + right * x + up * y);
    const Vec3 o = c.position - center;
    const float b = dot(o, d);
    return b * b - (dot(o, o) - radius * radius) > 0;
  };
  std::vector<bool> mask(static_cast<size_t>(c.width) * c.height);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      mask[static_cast<size_t>(y) * c.width + x] =
          hits(x, y) && hits(x + 1.0f, y) && hits(x, y + 1.0f) && hits(x + 1.0f, y + 1.0f);
    }
  }
  return mask;
}

std::vector<std::vector<bool>> blocks(const Film& film, const std::vector<bool>& mask, int block,
                                      int min_pixels) {
  std::vector<std::vector<bool>> out;
  for (int by = 0; by < film.height; by += block) {
    for (int bx = 0; bx < film.width; bx += block) {
      std::vector<bool> m(mask.size(), false);
      int count = 0;
      for (int y = by; y < std::min(by + block, film.height); ++y) {
        for (int x = bx; x < std::min(bx + block, film.width); ++x) {
          const size_t i = static_cast<size_t>(y) * film.width + x;
          if (mask[i]) {
            m[i] = true;
            ++count;
          }
        }
      }
      if (count >= min_pixels) out.push_back(std::move(m));
    }
  }
  return out;
}

int expect_same_region(const Film& a, const Film& b, const std::vector<bool>& mask, int block,
                       int min_pixels, const std::string& what) {
  const RegionStats ra = region_mean(a, mask), rb = region_mean(b, mask);
  EXPECT_LT(z_score(ra.mean, ra.standard_error, rb.mean, rb.standard_error), 4.0)
      << what << ": " << ra.mean << " +- " << ra.standard_error << " vs " << rb.mean << " +- "
      << rb.standard_error;
  int compared = 0;
  for (const auto& region : blocks(a, mask, block, min_pixels)) {
    const RegionStats ba = region_mean(a, region), bb = region_mean(b, region);
    if (!(ba.standard_error < 0.1 * ba.mean && bb.standard_error < 0.1 * bb.mean)) continue;
    ++compared;
    const size_t first =
        static_cast<size_t>(std::find(region.begin(), region.end(), true) - region.begin());
    EXPECT_LT(z_score(ba.mean, ba.standard_error, bb.mean, bb.standard_error), 5.0)
        << what << " block at (" << first % a.width << ", " << first / a.width << "): " << ba.mean
        << " +- " << ba.standard_error << " vs " << bb.mean << " +- " << bb.standard_error;
  }
  return compared;
}

int expect_same_image(const Film& a, const Film& b, const std::string& what) {
  const int edge = a.width / 4;
  return expect_same_region(a, b, std::vector<bool>(a.mean.size(), true), edge, edge * edge, what);
}

void add_panel_emitter(Scene& scene, Rgb emission) {
  Shape emitter;
  emitter.name = "panel";
  emitter.kind = ShapeKind::kMesh;
  emitter.mesh.positions = {{-1, 3, -1}, {1, 3, -1}, {1, 3, 1}, {-1, 3, 1}};
  emitter.mesh.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise from below: emits downward
  emitter.emission = emission;
  emitter.closed = false;
  emitter.material = 0;
  scene.shapes.push_back(emitter);
  Light panel;
  panel.kind = LightKind::kArea;
  panel.shape = static_cast<int>(scene.shapes.size() - 1);
  scene.lights.push_back(panel);
}

void light_by_panel_and_bulb(Scene& scene) {
  scene.lights.clear();
  add_panel_emitter(scene, Rgb(1.5f));
  Light bulb;
  bulb.kind = LightKind::kPoint;
  bulb.position = {2.5f, 0.5f, 1.5f};
  bulb.intensity = Rgb(6.0f);
  scene.lights.push_back(bulb);
}

void expect_renders_to_one(const Film& film) {
  // Every pixel is judged, background included (it sees the environment directly).
  const std::vector<bool> all(film.mean.size(), true);
  const RegionStats whole = region_mean(film, all);
  // Float accumulation over a path allows a few ulps of drift even where the estimator has
  // zero variance (pt with Fresnel-proportional choices).
  const double rounding = 1e-5;
  EXPECT_NEAR(whole.mean, 1.0, 4 * whole.standard_error + rounding)
      << "se " << whole.standard_error;
  // No region far off: 8x8 blocks, each within 5 standard errors (about 16 blocks, so a
  // Bonferroni-safe bound at a 1e-6 per-block false alarm rate).
  for (const auto& block : blocks(film, all, 8, 16)) {
    const RegionStats r = region_mean(film, block);
    EXPECT_NEAR(r.mean, 1.0, 5 * r.standard_error + rounding)
        << "block of " << r.pixels << " pixels";
  }
}

}  // namespace snee::test
