// `snee render --resume` as a user meets it (docs/resume.md): a render killed at any moment
// after its first checkpoint, resumed (stopped and resumed again, with other thread counts),
// writes the image the uninterrupted render writes, bit for bit, with or without a noise
// target; a checkpoint another render left, or a damaged one, is refused naming the file and
// what differs.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "apps/checkpoint_file.h"
#include "scene/film.h"
#include "tests/support/cli_fixture.h"
#include "tests/support/command_line.h"
#include "tests/support/render_helpers.h"
#include "tests/support/test_directory.h"
#include "tests/support/test_size.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

using test::contains;

class ResumeCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("resume_cli"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Exit code of `snee render ARGS`; its output is in output().
  int render(const std::string& args) const {
    return test::run_command("cd '" + dir_.string() + "' && '" SNEE_BINARY "' render " + args,
                             dir_ / "output.txt");
  }
  std::string output() const { return test::read_text_file(dir_ / "output.txt"); }
  // `snee render` with `args` in the background, writing `exr`.
  std::unique_ptr<test::BackgroundCommand> start(const std::vector<std::string>& args,
                                                 const std::string& exr) const {
    std::vector<std::string> argv = {SNEE_BINARY, "render"};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.insert(argv.end(), {"--quiet", "-o", exr});
    return std::make_unique<test::BackgroundCommand>(argv, dir_ / "background.txt");
  }
  void kill_and_resume_twice(const std::vector<std::string>& scene_args) const;
  fs::path dir_;
};

std::string joined(const std::vector<std::string>& args) {
  std::string text;
  for (const std::string& a : args) text += a + " ";
  return text;
}

// Waits for `file` to be written after `since` (a time point of the file system's clock).
bool written_after(const fs::path& file, fs::file_time_type since) {
  return test::wait_for([&] {
    std::error_code ec;
    const auto t = fs::last_write_time(file, ec);
    return !ec && t > since;
  });
}

// Renders `scene_args` uninterrupted, then again killed with SIGKILL at a random moment after
// its first checkpoint, resumed on another thread count and stopped with SIGTERM after the
// resumed render's own first checkpoint, and resumed once more on a third thread count: the
// last image must be the uninterrupted one.
void ResumeCli::kill_and_resume_twice(const std::vector<std::string>& scene_args) const {
  const std::string reference = path("reference.exr");
  ASSERT_EQ(render(joined(scene_args) + "--threads 2 --quiet -o " + reference), 0) << output();

  const std::string exr = path("stopped.exr");
  const fs::path state = checkpoint_path(exr, 0, 1);
  std::vector<std::string> first = scene_args;
  first.insert(first.end(), {"--threads", "2", "--checkpoint", "0.05"});
  {
    const auto run = start(first, exr);
    ASSERT_TRUE(test::wait_for([&] { return fs::exists(state); })) << run->output();
    std::mt19937 random(std::random_device{}());
    std::this_thread::sleep_for(
        std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 300)(random)));
    ASSERT_EQ(run->signal_and_wait(SIGKILL), 128 + SIGKILL)
        << "the render ended before it was killed: make it longer\n"
        << run->output();
  }
  std::vector<std::string> second = scene_args;
  second.insert(second.end(), {"--threads", "1", "--checkpoint", "0.05", "--resume", exr});
  {
    const auto since = fs::last_write_time(state);
    const auto run = start(second, exr);
    ASSERT_TRUE(written_after(state, since)) << run->output();
    const int code = run->signal_and_wait(SIGTERM);
    // The resumed render may have had little left; then it ended on its own.
    ASSERT_TRUE(code == 128 + SIGTERM || code == 0) << code << "\n" << run->output();
  }
  ASSERT_EQ(render(joined(scene_args) + "--threads 3 --quiet --resume " + exr), 0) << output();
  EXPECT_TRUE(contains(output(), "wrote " + exr)) << output();
  const Film a = read_exr(reference), b = read_exr(exr);
  EXPECT_TRUE(test::bitwise_identical(a, b));
  EXPECT_EQ(a.pixel_spp, b.pixel_spp);
  EXPECT_EQ(a.meta.min_spp, b.meta.min_spp);
}

TEST_F(ResumeCli, KilledStoppedAndResumedRenderIsBitwiseTheUninterruptedOne) {
  kill_and_resume_twice({"builtin:default", "--resolution", "48x32", "--spp",
                         std::to_string(test::sanitized_share(256)), "--samples-per-unit", "4"});
}

TEST_F(ResumeCli, NoiseTargetDecisionsSurviveTheResume) {
  kill_and_resume_twice({"builtin:sphere-directional-r0.2", "--resolution", "48x48", "--spp",
                         std::to_string(test::sanitized_share(512)), "--tile-size", "8",
                         "--samples-per-unit", "4", "--noise-target", "0.1"});
}

constexpr const char* kSmall = "builtin:furnace-sphere --resolution 16x16 --spp 16 --quiet ";

// A complete render with --checkpoint keeps its state; each render that differs from it in
// something that shapes the samples is refused before it renders, naming the file and both
// values.
TEST_F(ResumeCli, ACheckpointOfAnotherRenderIsRefused) {
  const std::string exr = path("small.exr");
  ASSERT_EQ(render(std::string(kSmall) + "--checkpoint 100 -o " + exr), 0) << output();
  const std::string state = checkpoint_path(exr, 0, 1).string();
  ASSERT_TRUE(fs::exists(state));
  const struct {
    std::string args, expected;
  } cases[] = {
      {std::string(kSmall) + "--seed 5", "seed 0 (this render: 5)"},
      {std::string(kSmall) + "--integrator snee", "integrator pt (this render: snee)"},
      {"builtin:furnace-sphere --resolution 16x8 --spp 16 --quiet",
       "resolution 16x16 (this render: 16x8)"},
      {std::string(kSmall) + "--max-depth 3", "max depth"},
      {std::string(kSmall) + "--tile-size 4", "tile size 16 (this render: 4)"},
      {std::string(kSmall) + "--noise-target 0.2", "noise target 0"},
      {"builtin:default --resolution 16x16 --spp 16 --quiet", "scene fnv1a64:"},
      {"builtin:furnace-sphere --resolution 16x16 --spp 8 --quiet", "--spp 16, this render has 8"},
  };
  for (const auto& c : cases) {
    const std::string out = path("other.exr");
    EXPECT_EQ(render(c.args + " --resume " + exr + " -o " + out), 1) << c.args;
    EXPECT_TRUE(contains(output(), "cannot resume from '" + state + "'")) << output();
    EXPECT_TRUE(contains(output(), c.expected)) << c.args << "\n" << output();
    EXPECT_FALSE(fs::exists(out)) << c.args << ": rendered anyway";
  }
  // More samples than the state's, its chunks being whole: it goes on, to the image of a render
  // asked for them at first.
  ASSERT_EQ(render("builtin:furnace-sphere --resolution 16x16 --spp 24 --quiet --resume " + exr), 0)
      << output();
  ASSERT_EQ(
      render("builtin:furnace-sphere --resolution 16x16 --spp 24 --quiet -o " + path("direct.exr")),
      0)
      << output();
  EXPECT_TRUE(test::bitwise_identical(read_exr(exr), read_exr(path("direct.exr"))));
}

TEST_F(ResumeCli, ADamagedOrMissingCheckpointIsRefused) {
  const std::string exr = path("small.exr");
  ASSERT_EQ(render(std::string(kSmall) + "--checkpoint 100 -o " + exr), 0) << output();
  const fs::path state = checkpoint_path(exr, 0, 1);
  std::string bytes = test::read_text_file(state);
  const auto resume_says = [&](const std::string& contents, const std::string& expected) {
    std::ofstream(state, std::ios::binary | std::ios::trunc) << contents;
    EXPECT_EQ(render(std::string(kSmall) + "--resume " + exr), 1) << expected;
    EXPECT_TRUE(contains(output(), "cannot resume from '" + state.string() + "': " + expected))
        << output();
  };
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  resume_says(flipped, "it is corrupt or truncated");
  resume_says(bytes.substr(0, bytes.size() - 100), "it is corrupt or truncated");
  resume_says(bytes.substr(0, 10), "it is not a snee checkpoint file");
  resume_says("P6 16 16 255\n", "it is not a snee checkpoint file");
  fs::remove(state);
  EXPECT_EQ(render(std::string(kSmall) + "--resume " + exr), 1);
  EXPECT_TRUE(contains(output(), "cannot resume from '" + state.string() + "': no such file"))
      << output();
}

// Another snee version's state (written here through the same code with the version changed,
// as no other version is at hand) is refused by name.
TEST(CheckpointFile, AnotherSneeVersionIsRefused) {
  const fs::path dir = test::fresh_test_directory("checkpoint_file");
  CheckpointIdentity identity;
  identity.fields = {{"snee version", SNEE_VERSION}, {"seed", 1}};
  identity.spp = 8;
  identity.samples_per_unit = 4;
  FilmState state;
  state.tiles = {{2, false}};
  state.sums.assign(kSumsPerPixel, 0.5);
  state.seconds = 1.5;
  CheckpointIdentity old = identity;
  old.fields["snee version"] = "0.0.1";
  const fs::path file = dir / "x.exr.checkpoint";
  write_checkpoint(file, old, state);
  try {
    read_checkpoint(file, identity);
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(contains(e.what(), "snee version 0.0.1 (this render: " SNEE_VERSION ")"))
        << e.what();
  }
  // The same identity reads back exactly what was written.
  write_checkpoint(file, identity, state);
  const FilmState back = read_checkpoint(file, identity);
  EXPECT_EQ(back.sums, state.sums);
  EXPECT_EQ(back.tiles.size(), 1u);
  EXPECT_EQ(back.tiles[0].chunks, 2u);
  EXPECT_EQ(back.seconds, 1.5);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snee
