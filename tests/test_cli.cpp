// The snee binary as a user meets it: help, usage errors, scene errors and a tiny render whose
// outputs are read back.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <thread>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/film.h"
#include "tests/support/command_line.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

std::string read_file(const fs::path& path) {
  return test::read_text_file(path);
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("snee_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `snee ARGS` in the temporary directory, so default outputs land there too.
  Outcome snee(const std::string& args) const {
    const fs::path log = dir_ / "output.txt";
    Outcome result;
    result.exit_code =
        test::run_command("cd '" + dir_.string() + "' && '" SNEE_BINARY "' " + args, log);
    result.output = read_file(log);
    return result;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(CliTest, RenderHelpListsEveryOption) {
  const Outcome run = snee("render --help");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  for (const char* option :
       {"SCENE", "builtin:", "--spp", "--threads", "--seed", "--integrator", "-o", "--output",
        "--stats", "--resolution", "--max-depth", "--queue-capacity", "--tile-size",
        "--samples-per-unit", "--schedule", "--checkpoint", "--quiet"})
    EXPECT_TRUE(contains(run.output, option)) << option << " missing from:\n" << run.output;
}

TEST_F(CliTest, TopLevelHelpAndVersion) {
  const Outcome help = snee("--help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_TRUE(contains(help.output, "render")) << help.output;
  EXPECT_TRUE(contains(help.output, "scenes")) << help.output;
  EXPECT_EQ(snee("scenes --help").exit_code, 0);

  const Outcome version = snee("--version");
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_TRUE(contains(version.output, SNEE_VERSION)) << version.output;
}

TEST_F(CliTest, NoSubcommandIsAnError) {
  const Outcome run = snee("");
  EXPECT_NE(run.exit_code, 0) << run.output;
}

TEST_F(CliTest, UnknownOptionIsAnError) {
  const Outcome run = snee("render --bogus-option 3");
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "--bogus-option")) << run.output;
}

TEST_F(CliTest, BadValuesAreErrors) {
  for (const char* args :
       {"render --resolution 0x5", "render --resolution 16", "render --resolution 16x-2",
        "render --spp 0", "render --spp many", "render --threads -1", "render --integrator bdpt",
        "render -o image.png", "render --tile-size 0"}) {
    const Outcome run = snee(args);
    EXPECT_NE(run.exit_code, 0) << args << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, "error")) << args << "\n" << run.output;
  }
}

TEST_F(CliTest, MissingSceneFileNamesThePath) {
  const std::string scene = path("no_such_scene.json");
  const Outcome run = snee("render '" + scene + "' --quiet");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, scene)) << run.output;
}

TEST_F(CliTest, MalformedJsonNamesFileAndLine) {
  const std::string scene = path("broken.json");
  write_file(scene, "{\n  \"camera\": {\n    \"fov\": 40,,\n  }\n}\n");
  const Outcome run = snee("render '" + scene + "' --quiet");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, scene)) << run.output;
  EXPECT_TRUE(contains(run.output, scene + ":3:15: malformed JSON")) << run.output;
}

TEST_F(CliTest, UnknownKeyNamesTheJsonPath) {
  const std::string scene = path("typo.json");
  write_file(scene, R"({"camera": {"fov": 40, "bogus_key": 1}})");
  const Outcome run = snee("render '" + scene + "' --quiet");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "camera.bogus_key")) << run.output;
}

TEST_F(CliTest, ScenesListsTheDefaultScene) {
  const Outcome run = snee("scenes");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "default")) << run.output;
  EXPECT_TRUE(contains(run.output, "furnace-sphere")) << run.output;
}

TEST_F(CliTest, TinyRenderWritesExrPngAndStats) {
  const Outcome run = snee(
      "render builtin:furnace-sphere --resolution 16x16 --spp 2 -o out/a.exr --stats s.json "
      "--quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "wrote out/a.exr")) << run.output;
  EXPECT_TRUE(contains(run.output, "wrote out/a.png")) << run.output;

  const Film film = read_exr(path("out/a.exr"));
  EXPECT_EQ(film.width, 16);
  EXPECT_EQ(film.height, 16);
  EXPECT_EQ(film.variance_of_mean.size(), 256u);
  EXPECT_EQ(film.meta.spp, 2);
  EXPECT_TRUE(fs::is_regular_file(path("out/a.png")));

  const auto stats = nlohmann::json::parse(read_file(path("s.json")));
  for (const char* key :
       {"version", "scene", "integrator", "spp", "complete", "min_spp", "seed", "threads",
        "resolution", "seconds", "stage_seconds", "rays", "paths", "mrays_per_second",
        "path_state_bytes_per_slot", "schedule", "queue_occupancy", "simd"})
    EXPECT_TRUE(stats.contains(key)) << key;
  // The camera kernel started every path: 16 x 16 x 2 active lanes, in whole batches.
  const auto& camera_lanes = stats["simd"]["kernels"]["generate"];
  EXPECT_EQ(camera_lanes["active_lanes"].get<uint64_t>(), 16u * 16u * 2u);
  EXPECT_EQ(camera_lanes["lanes_run"].get<uint64_t>() % stats["simd"]["width"].get<uint64_t>(), 0u);
  EXPECT_TRUE(stats["simd"]["kernels"].contains("medium_event"));
  EXPECT_EQ(stats["spp"], 2);
  EXPECT_EQ(stats["complete"], true);
  EXPECT_EQ(stats["min_spp"], 2);
  EXPECT_EQ(stats["resolution"]["width"], 16);
  EXPECT_EQ(stats["resolution"]["height"], 16);
  for (const char* kind : {"camera", "extension", "shadow", "probe", "total"})
    EXPECT_TRUE(stats["rays"].contains(kind)) << kind;
  EXPECT_GE(stats["rays"]["camera"].get<uint64_t>(), 16u * 16u * 2u);
}

TEST_F(CliTest, CheckpointedRenderEndsWithTheCompleteImageAndNoPartialFiles) {
  const Outcome run = snee(
      "render builtin:furnace-sphere --resolution 16x16 --spp 64 --samples-per-unit 1 "
      "--tile-size 4 --checkpoint 0.000001 -o out/c.exr --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Film film = read_exr(path("out/c.exr"));
  EXPECT_EQ(film.meta.spp, 64);
  EXPECT_EQ(film.meta.min_spp, 64);
  for (const auto& entry : fs::directory_iterator(path("out"))) {
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
  }
}

// Ctrl-C in the middle of a long render: the units in flight finish, the image so far is
// written, and the exit status is the shell's 128 + SIGINT.
TEST_F(CliTest, InterruptWritesTheImageSoFar) {
  const std::string exr = path("long.exr");
  const std::string log = path("long.txt");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(SNEE_BINARY, SNEE_BINARY, "render", "builtin:default", "--resolution", "64x48", "--spp",
          "1000000", "--checkpoint", "0.2", "-o", exr.c_str(), "--quiet", nullptr);
    _exit(127);
  }
  // The first checkpoint shows the render (and so the signal handler) has started.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(exr) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(exr)) << read_file(log);
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  pid_t done = 0;
  while ((done = waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() < deadline + std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (done == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    FAIL() << "snee did not stop after SIGINT: " << read_file(log);
  }
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << ": "
                                 << read_file(log);
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << read_file(log);
  EXPECT_TRUE(contains(read_file(log), "interrupted default after")) << read_file(log);
  const Film film = read_exr(exr);
  EXPECT_EQ(film.meta.spp, 1000000);
  EXPECT_LT(film.meta.min_spp, 1000000);
  EXPECT_GT(film.meta.render_seconds, 0.0);
}

TEST_F(CliTest, DefaultOutputIsNamedAfterTheScene) {
  const Outcome run = snee("render builtin:furnace-sphere --resolution 8x4 --spp 1 --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::is_regular_file(path("out/furnace-sphere.exr"))) << run.output;
  EXPECT_TRUE(fs::is_regular_file(path("out/furnace-sphere.png"))) << run.output;
  EXPECT_EQ(read_exr(path("out/furnace-sphere.exr")).width, 8);
}

TEST_F(CliTest, SneeStatsCountProbesAndConnections) {
  const Outcome run = snee(
      "render builtin:sphere-cone-r0.2 --integrator snee --resolution 16x16 --spp 2 --quiet "
      "--snee-strategies tb,ub,ul -o out/s.exr --stats s.json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto stats = nlohmann::json::parse(read_file(path("s.json")));
  EXPECT_EQ(stats["snee_options"]["strategies"], "tb,ub,ul");
  EXPECT_EQ(stats["snee_options"]["probe"], "uniform");
  const auto& c = stats["snee"];
  EXPECT_GT(c["probes"].get<uint64_t>(), 0u);
  EXPECT_EQ(c["probes"], stats["rays"]["probe"]);
  EXPECT_GT(c["top_to_bottom_connections"].get<uint64_t>(), 0u);
  EXPECT_EQ(c["bottom_to_top_connections"], 0) << "bt was not enabled";
  EXPECT_EQ(c["connection_rays"].get<uint64_t>(),
            3 * c["top_to_bottom_connections"].get<uint64_t>());
  EXPECT_EQ(snee("render builtin:sphere-cone-r0.2 --snee-strategies tb,xy").exit_code == 0, false);
}

TEST_F(CliTest, CompareWritesReportSheetAndRenders) {
  const Outcome run = snee(
      "compare builtin:sphere-cone-r0.2 --resolution 12x12 --spp 2 --reference-spp 4 -o cmp "
      "--quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* file : {"cmp/pt.exr", "cmp/snee.exr", "cmp/reference.exr", "cmp/compare.json",
                           "cmp/contact-sheet.png"})
    EXPECT_TRUE(fs::is_regular_file(path(file))) << file;
  const auto report = nlohmann::json::parse(read_file(path("cmp/compare.json")));
  EXPECT_EQ(report["mode"], "equal-spp");
  ASSERT_EQ(report["integrators"].size(), 2u);
  EXPECT_EQ(report["integrators"][0]["name"], "pt");
  EXPECT_EQ(report["integrators"][0]["efficiency_vs_first"], 1.0);
  for (const auto& entry : report["integrators"]) {
    EXPECT_EQ(entry["spp"], 2);
    EXPECT_GT(entry["relative_mse_raw"].get<double>(), 0.0);
  }
  // A reference of another size is an error, not a silently wrong report.
  const Outcome mismatch =
      snee("compare builtin:sphere-cone-r0.2 --resolution 8x8 --spp 1 --reference cmp/pt.exr");
  EXPECT_NE(mismatch.exit_code, 0);
  EXPECT_TRUE(contains(mismatch.output, "reference is 12x12")) << mismatch.output;
}

}  // namespace
}  // namespace snee
