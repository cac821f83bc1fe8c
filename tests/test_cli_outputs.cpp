// How the snee binary writes what it rendered, so that nothing rendered is lost and nothing
// half-written is left: checkpoints, Ctrl-C and SIGTERM, destinations checked before rendering,
// failed writes, partial files of dead processes, the longest names.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/interrupt_request.h"
#include "apps/output_files.h"
#include "scene/film.h"
#include "tests/support/cli_fixture.h"
#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using test::CliTest;
using test::contains;
using test::only_final_files;
using test::Outcome;
using test::read_text_file;
using test::write_file;

TEST_F(CliTest, CheckpointedRenderEndsWithTheCompleteImageAndNoPartialFiles) {
  const Outcome run = snee(
      "render builtin:furnace-sphere --resolution 16x16 --spp 64 --samples-per-unit 1 "
      "--tile-size 4 --checkpoint 0.000001 -o out/c.exr --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Film film = read_exr(path("out/c.exr"));
  EXPECT_EQ(film.meta.spp, 64);
  EXPECT_EQ(film.meta.min_spp, 64);
  EXPECT_TRUE(only_final_files(path("out")));
}

// Ctrl-C in the middle of a long render: the units in flight are dropped, the image so far
// is written, and the exit status is the shell's 128 + SIGINT.
TEST_F(CliTest, InterruptWritesTheImageSoFar) {
  const std::string exr = path("long.exr");
  const test::BackgroundCommand run(
      {SNEE_BINARY, "render", "builtin:default", "--resolution", "64x48", "--spp", "1000000",
       "--checkpoint", "0.2", "-o", exr, "--quiet"},
      path("long.txt"));
  // The first checkpoint shows the render (and so the signal handler) has started.
  ASSERT_TRUE(test::wait_for([&] { return fs::exists(exr); })) << run.output();
  const int code = run.signal_and_wait(SIGINT);
  ASSERT_EQ(code, 128 + SIGINT) << run.output();
  EXPECT_TRUE(contains(run.output(), "interrupted default after")) << run.output();
  const Film film = read_exr(exr);
  EXPECT_EQ(film.meta.spp, 1000000);
  EXPECT_LT(film.meta.min_spp, 1000000);
  EXPECT_GT(film.meta.render_seconds, 0.0);
}

// As many threads as the cap allows, many per core: SIGTERM still ends the render with the
// image written, because a stop drops the units in flight instead of waiting for all of them.
TEST_F(CliTest, ThreadsAboveTheLimitAreCappedAndSigtermIsHonoured) {
  const std::string exr = path("many.exr");
  const test::BackgroundCommand run(
      {SNEE_BINARY, "render", "builtin:default", "--resolution", "64x48", "--spp", "1000000",
       "--threads", "100000", "--checkpoint", "0.2", "-o", exr, "--quiet"},
      path("many.txt"));
  ASSERT_TRUE(test::wait_for([&] { return fs::exists(exr); })) << run.output();
  ASSERT_EQ(run.signal_and_wait(SIGTERM), 128 + SIGTERM) << run.output();
  EXPECT_TRUE(contains(run.output(), "warning: --threads 100000 is more than the limit of"))
      << run.output();
  const Film film = read_exr(exr);
  EXPECT_LT(film.meta.min_spp, film.meta.spp);
  EXPECT_TRUE(fs::is_regular_file(path("many.png")));
}

// A long checkpointed render whose output directory, once the first checkpoint is there, is
// replaced by a regular file, so the next checkpoint fails (and reports it).
std::unique_ptr<test::BackgroundCommand> render_into_a_vanished_directory(const CliTest& t) {
  const std::string exr = t.path("out/c.exr");
  auto run = std::make_unique<test::BackgroundCommand>(
      std::vector<std::string>{SNEE_BINARY, "render", "builtin:default", "--resolution", "32x24",
                               "--spp", "1000000", "--checkpoint", "0.05", "-o", exr, "--quiet"},
      t.path("c.txt"));
  EXPECT_TRUE(test::wait_for([&] { return fs::exists(exr); })) << run->output();
  // The render writes a checkpoint every 0.05 s and may create the directory again between the
  // removal and the write (seen under load): repeat until the file stands in its way.
  for (int attempt = 0; attempt < 1000 && !fs::is_regular_file(t.path("out")); ++attempt) {
    std::error_code ignored;
    fs::remove_all(t.path("out"), ignored);
    write_file(t.path("out"), "in the way");
  }
  EXPECT_TRUE(fs::is_regular_file(t.path("out")));
  EXPECT_TRUE(test::wait_for([&] { return contains(run->output(), "checkpoint not written"); }))
      << run->output();
  return run;
}

// The failed checkpoint is reported and the render goes on; the next checkpoint, once the
// way is clear, is written.
TEST_F(CliTest, AFailedCheckpointIsReportedAndRetried) {
  const auto run = render_into_a_vanished_directory(*this);
  fs::remove(path("out"));
  ASSERT_TRUE(test::wait_for([&] { return fs::exists(path("out/c.exr")); })) << run->output();
  ASSERT_EQ(run->signal_and_wait(SIGTERM), 128 + SIGTERM) << run->output();
  EXPECT_LT(read_exr(path("out/c.exr")).meta.min_spp, 1000000);
  EXPECT_TRUE(only_final_files(path("out"))) << "a partial file was left behind";
}

// When the final write fails too, the render's failure is the exit code.
TEST_F(CliTest, AFailedFinalWriteExitsWithOne) {
  const auto run = render_into_a_vanished_directory(*this);
  EXPECT_EQ(run->signal_and_wait(SIGTERM), 1) << run->output();
  EXPECT_TRUE(contains(run->output(), "error: cannot write")) << run->output();
}

// Every destination is checked before any sampling: the spp here would take hours, so a
// check after the render would never be reached within the test's timeout.
TEST_F(CliTest, BadDestinationsFailBeforeRendering) {
  fs::create_directories(path("dir.exr"));
  fs::create_directories(path("pngdir.png"));
  write_file(path("file"), "a regular file");
  const std::string long_name(252, 'n');
  const struct {
    std::string options, reason;
  } cases[] = {
      {"-o '" + path(long_name + ".exr") + "'", "the name is 256 bytes long"},
      {"-o '" + path("dir.exr") + "'", "a directory of that name is in the way"},
      {"-o '" + path("pngdir.exr") + "'", "a directory of that name is in the way"},
      {"-o '" + path("file/a.exr") + "'", "cannot create directory"},
      {"-o '" + path("ok.exr") + "' --stats '" + path("file/sub/s.json") + "'",
       "cannot create directory"},
  };
  for (const auto& c : cases) {
    const Outcome run =
        snee("render builtin:default --resolution 64x48 --spp 100000000 --quiet " + c.options);
    EXPECT_EQ(run.exit_code, 1) << c.options << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, "error: cannot write")) << run.output;
    EXPECT_TRUE(contains(run.output, c.reason)) << c.options << "\n" << run.output;
  }
}

TEST(OutputFiles, TooLittleFreeSpaceIsAnErrorBeforeRendering) {
  const fs::path file = fs::temp_directory_path() / "snee_space_check.exr";
  try {
    check_destination(file, std::numeric_limits<uintmax_t>::max());
    FAIL() << "no file system has that much free";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(contains(e.what(), "bytes free")) << e.what();
  }
  EXPECT_NO_THROW(check_destination(file, 1));
  EXPECT_FALSE(fs::exists(partial_path(file)));
}

// A write that fails half-way leaves the old file as it was and no partial file.
TEST(OutputFiles, AFailedWriteLeavesNoPartialFile) {
  const fs::path dir = fs::temp_directory_path() / "snee_failed_write";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "a.exr";
  write_file(file, "old");
  EXPECT_THROW(replace_file(file,
                            [](const std::string& partial) {
                              write_file(partial, "half");
                              throw std::runtime_error("disk full");
                            }),
               std::runtime_error);
  EXPECT_EQ(read_text_file(file), "old");
  EXPECT_TRUE(only_final_files(dir));
  fs::remove_all(dir);
}

// Ctrl-C twice: the first asks the render to stop and write what it has; a second one while that
// image is being written ends the process at once, and the partial file goes with it. The old
// image stays as it was.
TEST(OutputFiles, ASecondSignalDuringAWriteRemovesThePartialFile) {
  const fs::path dir = test::fresh_test_directory("signal");
  const fs::path file = dir / "a.exr";
  write_file(file, "old");
  const pid_t child = ::fork();
  if (child == 0) {
    const InterruptRequest interrupt;
    std::raise(SIGINT);  // the first: a request, the process goes on
    if (!interrupt.requested()) ::_exit(3);
    replace_file(file, [](const std::string& partial) {
      write_file(partial, "half");
      std::raise(SIGINT);  // the second, in the middle of the write
    });
    ::_exit(4);  // not reached: the second signal ends the process
  }
  ASSERT_GT(child, 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_EQ(read_text_file(file), "old");
  EXPECT_TRUE(only_final_files(dir));
  fs::remove_all(dir);
}

// A process killed outright while writing (SIGKILL, the out-of-memory killer) leaves its partial
// file; the next write of the same file removes it once its process is gone and it is old
// enough that no writer on another host can still be at it. A live process's partial file, a
// fresh one and another file's stay.
TEST(OutputFiles, PartialFilesOfDeadProcessesAreRemoved) {
  const fs::path dir = fs::temp_directory_path() / "snee_stale_partials";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "a.exr";
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ASSERT_GT(dead, 0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  const auto name_for = [&](const fs::path& f, pid_t pid) {
    return dir / ("." + f.stem().string() + "." + std::to_string(pid) + ".partial" +
                  f.extension().string());
  };
  const auto age = [](const fs::path& p, std::chrono::seconds by) {
    fs::last_write_time(p, fs::file_time_type::clock::now() - by);
  };
  const fs::path stale = name_for(file, dead), live = name_for(file, ::getppid()),
                 other = name_for(dir / "b.exr", dead);
  ASSERT_EQ(partial_path(file).filename(), name_for(file, ::getpid()).filename());
  for (const fs::path& p : {stale, live, other}) {
    write_file(p, "half");
    age(p, std::chrono::hours(2));
  }
  remove_stale_partial_files(file, kStalePartialAge);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other));
  // A dead process's file written just now (a writer elsewhere may still own it) stays.
  write_file(stale, "half");
  remove_stale_partial_files(file, kStalePartialAge);
  EXPECT_TRUE(fs::exists(stale));
  age(stale, std::chrono::hours(2));
  replace_file(file, [](const std::string& partial) { write_file(partial, "whole"); });
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(read_text_file(file), "whole");
  fs::remove_all(dir);
}

// The partial sibling of a name of NAME_MAX bytes still fits: the render's EXR and PNG are
// written under names of 255 bytes.
TEST_F(CliTest, OutputNamesOfNameMaxBytesWork) {
  const std::string stem(251, 's');
  const Outcome run = snee(
      "render builtin:furnace-sphere --resolution 8x8 --spp 1 --quiet "
      "--checkpoint 0.000001 -o '" +
      path(stem + ".exr") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(read_exr(path(stem + ".exr")).width, 8);
  EXPECT_TRUE(fs::is_regular_file(path(stem + ".png")));
  EXPECT_LE(partial_path(path(stem + ".exr")).filename().string().size(), 255u);
  EXPECT_TRUE(only_final_files(dir_));
}

}  // namespace
}  // namespace snee
