// Volumes that meet: every way two shapes can cross or nest is found (spheres, meshes, a sphere
// through a face with no edge inside it, a cube poking through a face), shapes that only touch
// or lie apart are not, and the loader refuses nested and overlapping volumes naming both shapes
// by their JSON paths, and warns of an opaque shape inside a medium.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "scene/scene_loader.h"
#include "scene/volume_overlap.h"
#include "tests/support/scene_error_of.h"
#include "tests/support/unit_cube.h"

namespace snee {
namespace {

using nlohmann::json;
using test::scene_error_of;
using test::unit_cube;

constexpr int kGlass = 0;   // dielectric: makes a closed shape a volume
constexpr int kOpaque = 1;  // diffuse

Scene two_materials() {
  Scene scene;
  Material glass;
  glass.kind = MaterialKind::kDielectric;
  scene.materials.push_back(glass);
  scene.materials.push_back(Material{});
  return scene;
}

void add_sphere(Scene& scene, Vec3 center, float radius, int material) {
  Shape s;
  s.kind = ShapeKind::kSphere;
  s.center = center;
  s.radius = radius;
  s.material = material;
  scene.shapes.push_back(s);
}

// The unit cube scaled by `size` about its corner and moved to `corner`.
void add_cube(Scene& scene, Vec3 corner, float size, int material) {
  Shape s;
  s.mesh = unit_cube();
  for (Vec3& p : s.mesh.positions) p = corner + p * size;
  s.material = material;
  scene.shapes.push_back(s);
}

// A square in the plane z = `z`, from (-half, -half) to (half, half): open, two triangles.
void add_square(Scene& scene, float z, float half, int material) {
  Shape s;
  s.mesh.positions = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
  s.mesh.indices = {0, 1, 2, 0, 2, 3};
  s.closed = false;
  s.material = material;
  scene.shapes.push_back(s);
}

void expect_contact(const Scene& scene, int volume, int other, bool inside) {
  const std::vector<VolumeContact> contacts = find_volume_contacts(scene);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].volume, volume);
  EXPECT_EQ(contacts[0].other, other);
  EXPECT_EQ(contacts[0].inside, inside);
}

TEST(VolumeOverlap, SpheresApartOrTouchingAreNoContact) {
  Scene scene = two_materials();
  add_sphere(scene, {0, 0, 0}, 1, kGlass);
  add_sphere(scene, {3, 0, 0}, 1, kGlass);
  add_sphere(scene, {0, 2, 0}, 1, kGlass);  // touches the first at one point
  EXPECT_TRUE(find_volume_contacts(scene).empty());
}

TEST(VolumeOverlap, OverlappingAndNestedSpheres) {
  Scene overlapping = two_materials();
  add_sphere(overlapping, {0, 0, 0}, 1, kGlass);
  add_sphere(overlapping, {1.5f, 0, 0}, 1, kGlass);
  expect_contact(overlapping, 0, 1, false);

  Scene nested = two_materials();
  add_sphere(nested, {0.1f, 0, 0}, 0.5f, kGlass);
  add_sphere(nested, {0, 0, 0}, 2, kGlass);
  expect_contact(nested, 1, 0, true);  // the inner one is `other`, whatever the order
}

TEST(VolumeOverlap, SphereAndCube) {
  Scene inside = two_materials();
  add_cube(inside, {-2, -2, -2}, 4, kGlass);
  add_sphere(inside, {0, 0, 0}, 1, kGlass);
  expect_contact(inside, 0, 1, true);

  Scene cube_in_sphere = two_materials();
  add_sphere(cube_in_sphere, {0.5f, 0.5f, 0.5f}, 3, kGlass);
  add_cube(cube_in_sphere, {0, 0, 0}, 1, kGlass);
  expect_contact(cube_in_sphere, 0, 1, true);

  // The sphere bulges through the middle of a face: no cube edge or vertex is inside it.
  Scene through_face = two_materials();
  add_cube(through_face, {-5, -5, -5}, 10, kGlass);
  add_sphere(through_face, {0, 0, 5}, 1, kGlass);
  expect_contact(through_face, 0, 1, false);

  Scene apart = two_materials();
  add_cube(apart, {0, 0, 0}, 1, kGlass);
  add_sphere(apart, {3, 0.5f, 0.5f}, 1, kGlass);
  EXPECT_TRUE(find_volume_contacts(apart).empty());
}

TEST(VolumeOverlap, CubesCrossingNestedAndApart) {
  // A small cube poking through the middle of a big cube's face: only the small one's edges
  // cross the other's surface.
  Scene poking = two_materials();
  add_cube(poking, {-5, -5, -5}, 10, kGlass);
  add_cube(poking, {-0.5f, -0.5f, 4.5f}, 1, kGlass);
  expect_contact(poking, 0, 1, false);

  Scene nested = two_materials();
  add_cube(nested, {0.25f, 0.25f, 0.25f}, 0.5f, kGlass);
  add_cube(nested, {0, 0, 0}, 1, kGlass);
  expect_contact(nested, 1, 0, true);

  Scene apart = two_materials();
  add_cube(apart, {0, 0, 0}, 1, kGlass);
  add_cube(apart, {1.5f, 0, 0}, 1, kGlass);
  EXPECT_TRUE(find_volume_contacts(apart).empty());
}

TEST(VolumeOverlap, OpaqueShapesCountOnlyInsideAVolume) {
  // A floor through a glass sphere is in contact; one under it, touching, is not.
  Scene floor_through = two_materials();
  add_sphere(floor_through, {0, 0, 0}, 1, kGlass);
  add_square(floor_through, 0.5f, 4, kOpaque);
  expect_contact(floor_through, 0, 1, false);

  Scene resting = two_materials();
  add_sphere(resting, {0, 0, 1}, 1, kGlass);
  add_square(resting, 0, 4, kOpaque);
  EXPECT_TRUE(find_volume_contacts(resting).empty());

  // A glass sphere inside a closed opaque room is fine; an opaque cube inside the glass is not.
  Scene room = two_materials();
  add_cube(room, {-5, -5, -5}, 10, kOpaque);
  add_sphere(room, {0, 0, 0}, 1, kGlass);
  EXPECT_TRUE(find_volume_contacts(room).empty());

  Scene core = two_materials();
  add_sphere(core, {0, 0, 0}, 2, kGlass);
  add_cube(core, {-0.5f, -0.5f, -0.5f}, 1, kOpaque);
  expect_contact(core, 0, 1, true);

  // Two opaque shapes are never looked at.
  Scene opaque = two_materials();
  add_sphere(opaque, {0, 0, 0}, 1, kOpaque);
  add_sphere(opaque, {0.5f, 0, 0}, 1, kOpaque);
  EXPECT_TRUE(find_volume_contacts(opaque).empty());
}

TEST(VolumeOverlap, AMediumMakesAVolumeAndAnOpenMeshIsNone) {
  Scene scene = two_materials();
  Material null_boundary;
  null_boundary.kind = MaterialKind::kNull;
  scene.materials.push_back(null_boundary);
  scene.media.push_back(Medium{});
  add_sphere(scene, {0, 0, 0}, 1, 2);
  scene.shapes.back().interior_medium = 0;
  add_sphere(scene, {0.5f, 0, 0}, 0.2f, 2);  // a null sphere without a medium bounds nothing
  add_square(scene, 3, 1, kGlass);           // an open glass sheet bounds nothing either
  EXPECT_TRUE(is_volume(scene, 0));
  EXPECT_FALSE(is_volume(scene, 1));
  EXPECT_FALSE(is_volume(scene, 2));
  // The null sphere is an opaque-side shape inside the medium: a contact, but not of volumes.
  expect_contact(scene, 0, 1, true);
}

json scene_document(const json& shapes) {
  return {{"camera", {{"position", {0, 0, 10}}, {"look_at", {0, 0, 0}}}},
          {"materials", json::array({{{"name", "glass"}, {"type", "dielectric"}, {"ior", 1.5}},
                                     {{"name", "floor"}, {"type", "diffuse"}}})},
          {"media",
           json::array({{{"name", "jade"}, {"sigma_s", 2}}, {{"name", "milk"}, {"sigma_s", 5}}})},
          {"shapes", shapes},
          {"lights", json::array({{{"type", "directional"}, {"direction", {0, 1, 1}}}})}};
}

TEST(VolumeOverlap, TheLoaderRefusesNestedMediaNamingBothShapes) {
  const json shapes = json::array({{{"type", "sphere"},
                                    {"name", "outer"},
                                    {"radius", 2},
                                    {"material", "glass"},
                                    {"medium", "jade"}},
                                   {{"type", "sphere"},
                                    {"name", "far"},
                                    {"center", {5, 0, 0}},
                                    {"material", "glass"},
                                    {"medium", "milk"}},
                                   {{"type", "sphere"},
                                    {"name", "inner"},
                                    {"radius", 0.5},
                                    {"material", "glass"},
                                    {"medium", "milk"}}});
  const std::string message =
      scene_error_of([&] { load_scene_json(scene_document(shapes), "nested.json", "/"); });
  EXPECT_NE(message.find("nested.json: shapes[2] ('inner') lies inside nested.json: shapes[0] "
                         "('outer')"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("Several media"), std::string::npos) << message;

  json overlapping = shapes;
  overlapping[2]["center"] = {4, 0, 0};  // now it overlaps "far"
  overlapping[2]["radius"] = 1.5;
  const std::string overlap_message =
      scene_error_of([&] { load_scene_json(scene_document(overlapping), "o.json", "/"); });
  EXPECT_NE(overlap_message.find("o.json: shapes[2] ('inner') overlaps o.json: shapes[1] ('far')"),
            std::string::npos)
      << overlap_message;
}

TEST(VolumeOverlap, TheLoaderWarnsOfAnOpaqueShapeInsideAMedium) {
  const json shapes =
      json::array({{{"type", "sphere"},
                    {"name", "wax"},
                    {"radius", 2},
                    {"material", "glass"},
                    {"medium", "jade"}},
                   {{"type", "quad"}, {"name", "floor"}, {"size", 10}, {"material", "floor"}}});
  const LoadedScene loaded = load_scene_json(scene_document(shapes), "w.json", "/");
  ASSERT_EQ(loaded.warnings.size(), 1u);
  const std::string& warning = loaded.warnings[0];
  EXPECT_NE(warning.find("w.json: shapes[1] ('floor') reaches into the volume w.json: shapes[0] "
                         "('wax')"),
            std::string::npos)
      << warning;
}

// The example of docs/scene-format.md ("Several media"): three volumes resting on a floor at a
// point each, so no contact and no warning.
TEST(VolumeOverlap, TheThreeMediaExampleLoadsWithoutWarnings) {
  const std::filesystem::path example =
      std::filesystem::path(SNEE_PROJECT_DATA_DIR).parent_path() / "docs/examples/three-media.json";
  const LoadedScene loaded = load_scene_file(example.string());
  ASSERT_EQ(loaded.scene.media.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(is_volume(loaded.scene, i));
  EXPECT_TRUE(find_volume_contacts(loaded.scene).empty());
  EXPECT_TRUE(loaded.warnings.empty());
}

}  // namespace
}  // namespace snee
