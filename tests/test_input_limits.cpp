// What a scene may make snee read and allocate: only regular files (input_file.h), and nothing
// beyond the memory budget (memory_budget.h), as the loaders and `snee render --max-memory` see
// it.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scene/input_file.h"
#include "scene/memory_budget.h"
#include "scene/scene_loader.h"
#include "tests/support/cli_fixture.h"
#include "tests/support/command_line.h"
#include "tests/support/icosphere.h"
#include "tests/support/scene_error_of.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

class InputLimitsTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("test_input_limits"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& contents) const {
    std::ofstream(path(name), std::ios::binary) << contents;
    return path(name);
  }
  std::string fifo(const std::string& name) const {
    EXPECT_EQ(::mkfifo(path(name).c_str(), 0600), 0) << std::strerror(errno);
    return path(name);
  }

  fs::path dir_;
};

using test::scene_error_of;

TEST(MemoryBudget, ParsesSizesAsPeopleWriteThem) {
  EXPECT_EQ(parse_byte_size("1000000"), 1000000u);
  EXPECT_EQ(parse_byte_size("512M"), uint64_t{512} << 20);
  EXPECT_EQ(parse_byte_size("4g"), uint64_t{4} << 30);
  EXPECT_EQ(parse_byte_size("1.5GiB"), uint64_t{3} << 29);
  EXPECT_EQ(parse_byte_size("2TB"), uint64_t{2} << 40);
  EXPECT_EQ(parse_byte_size("64kb"), uint64_t{64} << 10);
  for (const char* bad : {"", "G", "0", "-1G", "4X", "4 G", "iB", "4iB", "nan", "inf", "1e3",
                          "18446744073709551616", "17179869184G"}) {
    EXPECT_FALSE(parse_byte_size(bad)) << bad;
  }
}

TEST(MemoryBudget, FormatsAndSaturates) {
  EXPECT_EQ(format_bytes(177), "177 bytes");
  EXPECT_EQ(format_bytes(uint64_t{12} << 30), "12.0 GiB");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
  EXPECT_EQ(saturating_multiply(uint64_t{1} << 40, uint64_t{1} << 40), UINT64_MAX);
  EXPECT_EQ(saturating_add(UINT64_MAX, 1), UINT64_MAX);
  EXPECT_EQ(saturating_multiply(3, 4), 12u);
  // The default is the machine's memory, which sysconf reports here.
  EXPECT_EQ(MemoryBudget{}.bytes, physical_memory_bytes());
  EXPECT_GT(physical_memory_bytes(), uint64_t{64} << 20);
}

TEST_F(InputLimitsTest, ReadsRegularFilesWhole) {
  const std::string text(100000, 'x');
  EXPECT_EQ(read_input_file(write("a.txt", text), "test file", MemoryBudget{}), text);
  EXPECT_EQ(read_input_file(write("empty.txt", ""), "test file", MemoryBudget{}), "");
  // Through a symbolic link, what counts is the file it names.
  fs::create_symlink(dir_ / "a.txt", dir_ / "link.txt");
  EXPECT_EQ(read_input_file(path("link.txt"), "test file", MemoryBudget{}), text);
}

TEST_F(InputLimitsTest, RefusesAnythingButARegularFile) {
  const MemoryBudget budget;
  const std::string pipe = fifo("pipe");
  EXPECT_EQ(scene_error_of([&] { read_input_file(pipe, "test file", budget); }),
            pipe + ": cannot read test file: it is a FIFO, not a regular file");
  EXPECT_EQ(scene_error_of([&] { read_input_file("/dev/zero", "test file", budget); }),
            "/dev/zero: cannot read test file: it is a character device, not a regular file");
  EXPECT_EQ(scene_error_of([&] { read_input_file(dir_.string(), "test file", budget); }),
            dir_.string() + ": cannot read test file: it is a directory, not a regular file");
  const std::string missing = path("missing");
  EXPECT_EQ(scene_error_of([&] { read_input_file(missing, "test file", budget); }),
            missing + ": cannot read test file: no such file or directory");
  EXPECT_EQ(scene_error_of([&] { require_regular_file(pipe, "test file"); }),
            pipe + ": cannot read test file: it is a FIFO, not a regular file");
}

TEST_F(InputLimitsTest, RefusesAFileBeyondTheBudget) {
  const std::string big = write("big.txt", std::string(5000, 'x'));
  EXPECT_EQ(scene_error_of([&] { read_input_file(big, "test file", MemoryBudget{4096}); }),
            big +
                ": cannot read test file: the file's bytes need 4.9 KiB, more than the memory "
                "budget of 4.0 KiB (--max-memory)");
}

// std::ifstream opened the FIFO and waited for a writer for ever; /dev/zero never ended.
TEST_F(InputLimitsTest, SceneFileMustBeARegularFile) {
  const std::string pipe = fifo("scene.json");
  EXPECT_EQ(scene_error_of([&] { load_scene(pipe); }),
            pipe + ": cannot read the scene file: it is a FIFO, not a regular file");
  fs::create_symlink("/dev/zero", dir_ / "zero.json");
  EXPECT_NE(scene_error_of([&] { load_scene(path("zero.json")); }).find("it is a character device"),
            std::string::npos);
}

using test::Outcome;

class MaxMemoryCliTest : public InputLimitsTest {
 protected:
  Outcome snee(const std::string& args) const {
    Outcome result;
    result.exit_code = test::run_in_directory(dir_, SNEE_BINARY, args, result.output);
    return result;
  }
  // A triangle lit by a constant sky at `resolution`.
  std::string scene(const std::string& resolution) const {
    write("tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    return write("scene.json",
                 R"({"camera": {"type": "pinhole", "position": [0, 0, 4], "look_at": [0, 0, 0],
                     "up": [0, 1, 0], "fov": 30, "resolution": [)" +
                     resolution + R"(]},
                     "render": {"spp": 1},
                     "materials": [{"name": "d", "type": "diffuse", "albedo": [0.5, 0.5, 0.5]}],
                     "shapes": [{"type": "mesh", "file": "tri.obj", "material": "d"}],
                     "lights": [{"type": "constant", "radiance": [1, 1, 1]}]})");
  }
};

TEST_F(MaxMemoryCliTest, RejectsWhatIsNotASize) {
  const Outcome out = snee("render --max-memory lots " + scene("8, 8"));
  EXPECT_NE(out.exit_code, 0);
  EXPECT_NE(out.output.find("--max-memory: expected a size such as 4G, 512M or 1000000, got "
                            "'lots'"),
            std::string::npos)
      << out.output;
}

// A 65536^2 film died of std::bad_alloc (or the OOM killer) part-way into allocating it; the
// largest film a scene may ask for (kMaxImageEdge^2) is counted against the budget first.
TEST_F(MaxMemoryCliTest, FilmBeyondTheBudgetFailsBeforeRendering) {
  const Outcome out = snee("render -q --threads 2 --max-memory 1G " + scene("32768, 32768"));
  EXPECT_EQ(out.exit_code, 1) << out.output;
  EXPECT_NE(out.output.find("the film and work buffers of 32768x32768 pixels on 2 threads need "
                            "76.5 GiB, more than the memory budget of 1.0 GiB (--max-memory)"),
            std::string::npos)
      << out.output;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "scene.exr"));
}

TEST_F(MaxMemoryCliTest, BudgetAppliesToTheSceneAndItsMeshes) {
  const std::string path = scene("8, 8");
  Outcome out = snee("render -q --max-memory 200 " + path);
  EXPECT_EQ(out.exit_code, 2) << out.output;
  EXPECT_NE(out.output.find("scene.json: cannot read the scene file: the file's bytes need"),
            std::string::npos)
      << out.output;
  out = snee("render -q --max-memory 8M " + path);
  EXPECT_EQ(out.exit_code, 0) << out.output;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "scene.exr"));
}

// SNEE's manifold strategy builds, for a closed flat-shaded mesh under a directional light, a
// tree over its facets (manifold_mesh.h) that grows with the mesh; it is counted against the
// budget too, after the mesh itself fit. A 20480-triangle icosphere's tree needs 3.2 MiB, its
// PLY arrays 0.4 MiB, its file 0.8 MiB and the 16x16 film on one thread 1.0 MiB; `pt` builds no
// tree, so the same scene renders there within the same budget, and `snee` within 4 MiB. Behind
// a rough boundary the guided exit builds the same tree, against the same budget.
TEST_F(MaxMemoryCliTest, ExitTreesBeyondTheBudgetFailBeforeRendering) {
  const TriangleMesh ball = test::icosphere(5, false);
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\nelement vertex " << ball.positions.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
      << ball.triangle_count() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : ball.positions) ply << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (size_t t = 0; t < ball.triangle_count(); ++t) {
    ply << "3 " << ball.indices[3 * t] << ' ' << ball.indices[3 * t + 1] << ' '
        << ball.indices[3 * t + 2] << '\n';
  }
  write("ball.ply", ply.str());
  // The glass is smooth, or rough (then the guided exit builds the tree: docs/method.md 3.15).
  const auto scene = [&](const std::string& roughness) {
    return write("scene.json",
                 R"({"camera": {"type": "pinhole", "position": [0, 0, 4], "look_at": [0, 0, 0],
                "up": [0, 1, 0], "fov": 30, "resolution": [16, 16]},
                "render": {"spp": 1},
                "materials": [{"name": "glass", "type": "dielectric", "ior": 1.5,
                               "roughness": )" +
                     roughness + R"(}],
                "media": [{"name": "milk", "sigma_s": [2, 2, 2], "sigma_a": [0.02, 0.02, 0.02]}],
                "shapes": [{"name": "ball", "type": "mesh", "file": "ball.ply",
                            "material": "glass", "medium": "milk"}],
                "lights": [{"type": "directional", "direction": [1, 1, 1], "irradiance": 1}]})");
  };
  const std::string path = scene("0");
  // Rendering with `integrator` within `budget` either fails before writing anything, saying
  // `refusal`, or (an empty refusal) writes the image.
  const auto expect_render = [&](const std::string& integrator, const std::string& budget,
                                 const std::string& refusal) {
    const Outcome out = snee("render -q --threads 1 --integrator " + integrator + " --max-memory " +
                             budget + " " + path);
    const fs::path image = dir_ / "out" / "scene.exr";
    if (refusal.empty()) {
      EXPECT_EQ(out.exit_code, 0) << out.output;
      EXPECT_TRUE(fs::exists(image));
      fs::remove(image);
    } else {
      EXPECT_EQ(out.exit_code, 1) << out.output;
      EXPECT_NE(out.output.find(refusal), std::string::npos) << out.output;
      EXPECT_FALSE(fs::exists(image));
    }
  };
  expect_render("snee", "2M",
                "the manifold strategy's exit trees of the mesh 'ball' (20480 triangles, a tree "
                "for each of 1 directional and 0 point or spot lights) need 3.2 MiB, more than "
                "the memory budget of 2.0 MiB (--max-memory)");
  expect_render("pt", "2M", "");
  expect_render("snee", "4M", "");
  scene("0.1");
  expect_render("snee", "2M",
                "the guided exit's exit trees of the mesh 'ball' (20480 triangles, a tree for "
                "each of 1 small distant lights) need 3.2 MiB");
  expect_render("snee", "4M", "");
}

}  // namespace
}  // namespace snee
