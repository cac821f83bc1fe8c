#include "tests/support/scene_comparison.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace snee::test {

void expect_same_transform(const Transform& a, const Transform& b) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_EQ(a.m[i][j], b.m[i][j]) << i << "," << j;
  }
}

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.camera.position, b.camera.position);
  EXPECT_EQ(a.camera.look_at, b.camera.look_at);
  EXPECT_EQ(a.camera.up, b.camera.up);
  EXPECT_EQ(a.camera.fov_degrees, b.camera.fov_degrees);
  EXPECT_EQ(a.camera.fov_axis, b.camera.fov_axis);
  EXPECT_EQ(a.camera.aperture_radius, b.camera.aperture_radius);
  EXPECT_EQ(a.camera.focus_distance, b.camera.focus_distance);
  EXPECT_EQ(a.camera.width, b.camera.width);
  EXPECT_EQ(a.camera.height, b.camera.height);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].kind, b.materials[i].kind);
    EXPECT_EQ(a.materials[i].albedo, b.materials[i].albedo);
    EXPECT_EQ(a.materials[i].ior, b.materials[i].ior);
    EXPECT_EQ(a.materials[i].roughness, b.materials[i].roughness);
    EXPECT_EQ(a.materials[i].transmittance, b.materials[i].transmittance);
    EXPECT_EQ(a.materials[i].conductor_eta, b.materials[i].conductor_eta);
    EXPECT_EQ(a.materials[i].conductor_k, b.materials[i].conductor_k);
  }
  ASSERT_EQ(a.media.size(), b.media.size());
  for (size_t i = 0; i < a.media.size(); ++i) {
    EXPECT_EQ(a.media[i].name, b.media[i].name);
    EXPECT_EQ(a.media[i].sigma_s, b.media[i].sigma_s);
    EXPECT_EQ(a.media[i].sigma_a, b.media[i].sigma_a);
    EXPECT_EQ(a.media[i].g, b.media[i].g);
  }
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  for (size_t i = 0; i < a.shapes.size(); ++i) {
    const Shape &s = a.shapes[i], &t = b.shapes[i];
    EXPECT_EQ(s.name, t.name);
    EXPECT_EQ(s.kind, t.kind);
    EXPECT_EQ(s.mesh.positions, t.mesh.positions);
    EXPECT_EQ(s.mesh.indices, t.mesh.indices);
    EXPECT_EQ(s.center, t.center);
    EXPECT_EQ(s.radius, t.radius);
    EXPECT_EQ(s.material, t.material);
    EXPECT_EQ(s.interior_medium, t.interior_medium);
    EXPECT_EQ(s.emission, t.emission);
    EXPECT_EQ(s.closed, t.closed);
    EXPECT_EQ(s.source, t.source);
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    const Light &l = a.lights[i], &m = b.lights[i];
    EXPECT_EQ(l.kind, m.kind);
    EXPECT_EQ(l.direction, m.direction);
    EXPECT_EQ(l.irradiance, m.irradiance);
    EXPECT_EQ(l.half_angle, m.half_angle);
    EXPECT_EQ(l.radiance, m.radiance);
    EXPECT_EQ(l.position, m.position);
    EXPECT_EQ(l.intensity, m.intensity);
    EXPECT_EQ(l.spot_axis, m.spot_axis);
    EXPECT_EQ(l.spot_cos_outer, m.spot_cos_outer);
    EXPECT_EQ(l.spot_cos_inner, m.spot_cos_inner);
    EXPECT_EQ(l.env_image, m.env_image);
    expect_same_transform(l.env_rotation, m.env_rotation);
    EXPECT_EQ(l.shape, m.shape);
  }
  ASSERT_EQ(a.env_images.size(), b.env_images.size());
  for (size_t i = 0; i < a.env_images.size(); ++i) {
    EXPECT_EQ(a.env_images[i].width, b.env_images[i].width);
    EXPECT_EQ(a.env_images[i].height, b.env_images[i].height);
    EXPECT_EQ(a.env_images[i].pixels, b.env_images[i].pixels);
    EXPECT_EQ(a.env_images[i].source, b.env_images[i].source);
  }
  EXPECT_EQ(a.render.spp, b.render.spp);
  EXPECT_EQ(a.render.max_depth, b.render.max_depth);
  EXPECT_EQ(a.render.seed, b.render.seed);
  EXPECT_EQ(a.render.integrator, b.render.integrator);
  EXPECT_EQ(a.render.light_selection, b.render.light_selection);
  EXPECT_EQ(a.render.noise_target, b.render.noise_target);
}

void expect_round_trip(const LoadedScene& first, const std::string& origin) {
  const LoadedScene second = load_scene_json(first.canonical, origin, "/");
  expect_same_scene(first.scene, second.scene);
  EXPECT_EQ(first.canonical, second.canonical) << first.canonical.dump(1) << "\n---\n"
                                               << second.canonical.dump(1);
}

double bounding_radius(const TriangleMesh& mesh, Vec3 center) {
  double r = 0;
  for (const Vec3& p : mesh.positions) r = std::max(r, double{length(p - center)});
  return r;
}

}  // namespace snee::test
