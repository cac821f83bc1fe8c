// Mesh topology (closedness, non-manifold edges, signed volume, orientation, the normalizing
// transform) that the scene loader relies on, on handmade meshes, the project's bunny and, where
// present, the shared test meshes.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "scene/mesh_io.h"
#include "scene/mesh_topology.h"
#include "tests/support/unit_cube.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

// The workplace's shared test meshes (../shared/data), too large for the repository: a machine
// without them (every fresh CI machine) reports these tests as skipped, never as passed. Where the
// folder is there, a missing mesh in it fails the test.
const fs::path kSharedMeshes = "/work/shared/data/meshes";

class SharedMeshes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kSharedMeshes)) GTEST_SKIP() << kSharedMeshes << " is not present";
  }
  static TriangleMesh shared_mesh(const std::string& name) {
    return load_mesh((kSharedMeshes / name).string());
  }
};

using test::unit_cube;

TEST(MeshTopology, CubeIsClosedWithUnitVolume) {
  TriangleMesh cube = unit_cube();
  const EdgeCounts edges = count_edges(cube);
  EXPECT_EQ(edges.boundary, 0u);
  EXPECT_EQ(edges.non_manifold, 0u);
  EXPECT_NEAR(signed_volume(cube), 1.0, 1e-12);
  flip_winding(cube);
  EXPECT_NEAR(signed_volume(cube), -1.0, 1e-12);
}

TEST(MeshTopology, VolumeDoesNotDependOnPosition) {
  TriangleMesh cube = unit_cube();
  apply_transform(Transform::translate(Vec3(100, -50, 7)) * Transform::scale(Vec3(2, 3, 0.5f)),
                  cube);
  EXPECT_NEAR(signed_volume(cube), 3.0, 1e-6);
}

TEST(MeshTopology, CountsBoundaryAndNonManifoldEdges) {
  TriangleMesh open = unit_cube();
  open.indices.resize(open.indices.size() - 6);  // remove the x = 1 face: a square hole
  EXPECT_EQ(count_edges(open).boundary, 4u);
  EXPECT_EQ(count_edges(open).non_manifold, 0u);

  // Three triangles on one edge (a "book" with three pages).
  TriangleMesh book;
  book.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
  book.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  const EdgeCounts edges = count_edges(book);
  EXPECT_EQ(edges.non_manifold, 1u);
  EXPECT_EQ(edges.boundary, 6u);
}

TEST(MeshTopology, NormalizingTransformGivesUnitBoundingSphere) {
  TriangleMesh m;
  m.positions = {{10, 20, 30}, {14, 20, 30}, {10, 23, 30}};
  m.indices = {0, 1, 2};
  apply_transform(normalizing_transform(m), m);
  // The box centre (12, 21.5, 30) goes to the origin; the farthest vertex is at 2.5.
  EXPECT_NEAR(m.positions[0].x, -0.8f, 1e-6f);
  EXPECT_NEAR(m.positions[0].y, -0.6f, 1e-6f);
  EXPECT_NEAR(m.positions[2].y, 0.6f, 1e-6f);
  EXPECT_NEAR(length(m.positions[0]), 1.0f, 1e-6f);
}

TEST(ProjectMeshes, BunnyNpmIsClosedAndOutward) {
  const TriangleMesh m = load_mesh(std::string(SNEE_PROJECT_DATA_DIR) + "/meshes/bunny-npm.obj");
  EXPECT_EQ(m.triangle_count(), 3674u);
  EXPECT_EQ(m.positions.size(), 1839u);
  const EdgeCounts edges = count_edges(m);
  EXPECT_EQ(edges.boundary, 0u);
  EXPECT_EQ(edges.non_manifold, 0u);
  EXPECT_GT(signed_volume(m), 0.0);
}

TEST(ProjectMeshes, ReorientingByVolumeFixesAnInsideOutBunny) {
  TriangleMesh m = load_mesh(std::string(SNEE_PROJECT_DATA_DIR) + "/meshes/bunny-npm.obj");
  const double volume = signed_volume(m);
  flip_winding(m);
  EXPECT_DOUBLE_EQ(signed_volume(m), -volume);
  if (signed_volume(m) < 0) flip_winding(m);
  EXPECT_DOUBLE_EQ(signed_volume(m), volume);
}

TEST_F(SharedMeshes, StanfordBunnyHas223BoundaryEdges) {
  const TriangleMesh m = shared_mesh("stanford-bunny.obj");
  EXPECT_EQ(m.triangle_count(), 69451u);
  EXPECT_EQ(m.positions.size(), 35947u);
  EXPECT_EQ(count_edges(m).boundary, 223u);
}

// The load time is recorded (in ctest's XML output), not asserted: a timed assertion fails on a
// busy machine.
TEST_F(SharedMeshes, DragonAsciiPlyLoads) {
  const auto start = std::chrono::steady_clock::now();
  const TriangleMesh m = shared_mesh("dragon_vrip.ply");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("load_seconds", std::to_string(seconds));
  EXPECT_EQ(m.triangle_count(), 871414u);
  EXPECT_EQ(m.positions.size(), 437645u);
  const EdgeCounts edges = count_edges(m);
  EXPECT_EQ(edges.boundary, 4270u);
}

TEST_F(SharedMeshes, DecimatedDragonHasNonManifoldEdges) {
  const TriangleMesh m = shared_mesh("dragon_vrip_res4.ply");
  EXPECT_EQ(m.triangle_count(), 11102u);
  EXPECT_EQ(m.positions.size(), 5205u);
  const EdgeCounts edges = count_edges(m);
  EXPECT_EQ(edges.boundary, 0u);
  EXPECT_EQ(edges.non_manifold, 803u);
}

}  // namespace
}  // namespace snee
