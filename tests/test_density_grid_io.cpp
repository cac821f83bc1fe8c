// Density grids in and out (scene/density_grid_io.h) and the scene format's grid media
// (docs/scene-format.md): a .vol file round trip, inline grids and the canonical form, and every
// bad input refused with a message that names the file or JSON path and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene/density_grid_io.h"
#include "scene/scene_loader.h"
#include "tests/support/scene_error_of.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::scene_error_of;

DensityGrid small_grid() {
  DensityGrid g;
  g.nx = 3, g.ny = 2, g.nz = 2;
  g.lo = {-1, -2, -3}, g.hi = {1, 2, 3.5f};
  for (int i = 0; i < 12; ++i) g.values.push_back(0.25f * static_cast<float>(i));
  return g;
}

class DensityGridIo : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("test_density_grid_io"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // The bytes of small_grid() as a .vol file, which the tests below corrupt.
  std::string vol_bytes() const {
    write_density_grid(path("good.vol"), small_grid());
    std::ifstream in(path("good.vol"), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  std::string write_bytes(const std::string& bytes) const {
    std::ofstream(path("bad.vol"), std::ios::binary) << bytes;
    return path("bad.vol");
  }
  static void put_int(std::string& bytes, size_t offset, int32_t v) {
    std::memcpy(bytes.data() + offset, &v, 4);  // the test machines are little-endian
  }
  static void put_float(std::string& bytes, size_t offset, float v) {
    std::memcpy(bytes.data() + offset, &v, 4);
  }

  // A scene with one grid medium whose "density" is `density`, loaded from the test directory.
  LoadedScene load_with_density(const json& density, const std::string& type = "grid") const {
    json medium = {{"name", "smoke"}, {"type", type}, {"sigma_s", 1}};
    if (!density.is_null()) medium["density"] = density;
    json doc = {{"camera", {{"position", {0, 0, 4}}, {"look_at", {0, 0, 0}}}},
                {"media", {medium}},
                {"materials", {{{"name", "clear"}, {"type", "null"}}}},
                {"shapes", {{{"type", "sphere"}, {"material", "clear"}, {"medium", "smoke"}}}}};
    return load_scene_json(doc, "scene.json", dir_.string());
  }

  fs::path dir_;
};

TEST_F(DensityGridIo, VolFileRoundTrips) {
  DensityGrid written = small_grid();
  write_density_grid(path("g.vol"), written);
  const DensityGrid read = read_density_grid(path("g.vol"), {});
  EXPECT_EQ(read.nx, 3);
  EXPECT_EQ(read.ny, 2);
  EXPECT_EQ(read.nz, 2);
  EXPECT_EQ(read.lo, written.lo);
  EXPECT_EQ(read.hi, written.hi);
  EXPECT_EQ(read.values, written.values);
  EXPECT_EQ(read.max_value, 2.75f);
  EXPECT_EQ(read.at(2, 1, 1), 2.75f);
  EXPECT_EQ(read.at(1, 0, 1), 1.75f);  // x fastest, then y, then z
  EXPECT_EQ(fs::file_size(path("g.vol")), 48u + 4u * 12u);
}

TEST_F(DensityGridIo, DensityIsTheVoxelsValueAndZeroOutside) {
  DensityGrid g = small_grid();
  validate_density_grid(g, "grid");
  EXPECT_EQ(g.density({-0.9f, -1.9f, -2.9f}), 0.0f);  // voxel (0, 0, 0)
  EXPECT_EQ(g.density({0.9f, 1.9f, 3.4f}), 2.75f);    // voxel (2, 1, 1)
  EXPECT_EQ(g.density({0.0f, -1.0f, -2.0f}), 0.25f);  // voxel (1, 0, 0)
  EXPECT_EQ(g.density({1.01f, 0.0f, 0.0f}), 0.0f);    // outside
  EXPECT_EQ(g.density({NAN, 0.0f, 0.0f}), 0.0f);
}

TEST_F(DensityGridIo, BadFilesNameTheFieldAndTheExpectation) {
  const std::string good = vol_bytes();
  const auto error_for = [&](const std::string& bytes) {
    const std::string p = write_bytes(bytes);
    return scene_error_of([&] { read_density_grid(p, {}); });
  };
  EXPECT_NE(error_for(good.substr(0, 20)).find("shorter than the 48-byte header"),
            std::string::npos);
  std::string b = good;
  b[0] = 'X';
  EXPECT_NE(error_for(b).find("does not start with 'VOL'"), std::string::npos);
  b = good, b[3] = 2;
  EXPECT_NE(error_for(b).find(".vol version 2; expected version 3"), std::string::npos);
  b = good, put_int(b, 4, 3);
  EXPECT_NE(error_for(b).find("encoding 3; expected 1 (float32)"), std::string::npos);
  b = good, put_int(b, 20, 3);
  EXPECT_NE(error_for(b).find("3 channels; expected 1"), std::string::npos);
  b = good, put_int(b, 12, 0);
  EXPECT_NE(error_for(b).find("resolution 3 x 0 x 2; expected at least 1 voxel"),
            std::string::npos);
  b = good, put_int(b, 8, 4);
  EXPECT_NE(error_for(b).find(
                "48 bytes of data after the header; expected 64 (4 per voxel of 4 x 2 x 2)"),
            std::string::npos);
  b = good, put_int(b, 8, 1 << 30), put_int(b, 12, 1 << 30);
  EXPECT_NE(error_for(b).find("its voxels need"), std::string::npos);  // over the memory budget
  EXPECT_NE(error_for(good.substr(0, good.size() - 4))
                .find("44 bytes of data after the header; expected 48"),
            std::string::npos);
  EXPECT_NE(error_for(good + "xxxx").find("52 bytes of data after the header; expected 48"),
            std::string::npos);
  b = good, put_float(b, 48 + 4 * 7, -1.0f);
  EXPECT_NE(error_for(b).find("voxel (1, 0, 1) has density -1"), std::string::npos);
  b = good, put_float(b, 48 + 4 * 11, NAN);
  EXPECT_NE(error_for(b).find("voxel (2, 1, 1) has density"), std::string::npos);
  b = good, put_float(b, 36, -1.0f);  // max x = min x
  EXPECT_NE(error_for(b).find("is empty or not finite"), std::string::npos);
  const std::string missing = scene_error_of([&] { read_density_grid(path("none.vol"), {}); });
  EXPECT_NE(missing.find(path("none.vol")), std::string::npos);
  MemoryBudget tiny;
  tiny.bytes = 64;
  const std::string p = write_bytes(good);
  EXPECT_NE(scene_error_of([&] { read_density_grid(p, tiny); }).find("memory budget"),
            std::string::npos);
}

TEST_F(DensityGridIo, SceneLoadsFileAndInlineGrids) {
  write_density_grid(path("smoke.vol"), small_grid());
  const LoadedScene from_file = load_with_density({{"file", "smoke.vol"}});
  ASSERT_TRUE(from_file.scene.media[0].density);
  EXPECT_EQ(from_file.scene.media[0].density->values, small_grid().values);
  EXPECT_EQ(from_file.scene.media[0].density->hi, small_grid().hi);
  const LoadedScene moved = load_with_density(
      {{"file", "smoke.vol"}, {"bounds", {{"min", {0, 0, 0}}, {"max", {2, 2, 2}}}}});
  EXPECT_EQ(moved.scene.media[0].density->hi, Vec3(2, 2, 2));

  const json inline_grid = {{"resolution", {2, 1, 1}},
                            {"values", {0.5, 3}},
                            {"bounds", {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}}}};
  const LoadedScene loaded = load_with_density(inline_grid);
  const DensityGrid& g = *loaded.scene.media[0].density;
  EXPECT_EQ(g.values, std::vector<float>({0.5f, 3.0f}));
  EXPECT_EQ(g.max_value, 3.0f);
  // The canonical form loads to the same grid.
  const LoadedScene again = load_scene_json(loaded.canonical, "canonical", dir_.string());
  EXPECT_EQ(again.scene.media[0].density->values, g.values);
  EXPECT_EQ(again.scene.media[0].density->lo, g.lo);
  EXPECT_EQ(loaded.canonical["media"][0]["type"], "grid");
  const LoadedScene homogeneous = load_with_density(nullptr, "homogeneous");
  EXPECT_FALSE(homogeneous.scene.media[0].density);
}

TEST_F(DensityGridIo, BadGridMediaNameTheJsonPath) {
  write_density_grid(path("smoke.vol"), small_grid());
  const json bounds = {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}};
  const auto error_for = [&](const json& density, const std::string& type = "grid") {
    return scene_error_of([&] { load_with_density(density, type); });
  };
  EXPECT_NE(error_for({{"file", "smoke.vol"}}, "homogeneous")
                .find("media[0].density: a density belongs to a medium of type \"grid\""),
            std::string::npos);
  EXPECT_NE(error_for({{"resolution", {1, 1, 1}}, {"values", {1}}, {"file", "smoke.vol"}})
                .find("expected either file"),
            std::string::npos);
  EXPECT_NE(error_for({{"resolution", {2, 2, 1}}, {"values", {1, 2, 3}}, {"bounds", bounds}})
                .find("media[0].density.values: expected an array of 4 densities"),
            std::string::npos);
  EXPECT_NE(error_for({{"resolution", {2, 1, 1}}, {"values", {1, -2}}, {"bounds", bounds}})
                .find("media[0].density.values[1]"),
            std::string::npos);
  EXPECT_NE(error_for({{"resolution", {2, 1, 1}}, {"values", {1, 2}}}).find("need bounds"),
            std::string::npos);
  EXPECT_NE(error_for({{"resolution", {2, 1, 1}},
                       {"values", {1, 2}},
                       {"bounds", {{"min", {1, 1, 1}}, {"max", {1, 2, 2}}}}})
                .find("is empty or not finite"),
            std::string::npos);
  EXPECT_NE(error_for({{"file", "nowhere.vol"}}).find("media[0].density.file"), std::string::npos);
  EXPECT_NE(error_for({{"file", "smoke.vol"}, {"resolution", {1, 1, 1}}})
                .find("a file gives its own resolution"),
            std::string::npos);
  EXPECT_NE(scene_error_of([&] {
              json doc = {{"camera", {{"position", {0, 0, 4}}, {"look_at", {0, 0, 0}}}},
                          {"media", {{{"name", "smoke"}, {"type", "grid"}, {"sigma_s", 1}}}}};
              load_scene_json(doc, "scene.json", dir_.string());
            }).find("media[0]"),
            std::string::npos);
}

}  // namespace
}  // namespace snee
