// snee-mpi under mpirun: processes on disjoint tiles, shared out statically or claimed while
// rendering by ranks with different thread counts, give the image `snee render` gives, bit
// for bit, and the merged statistics count every path and tile once; a signal to one process stops
// them all with its exit code, and a stopped process holds no other for ever.
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/film.h"
#include "tests/support/command_line.h"
#include "tests/support/render_helpers.h"
#include "tests/support/test_directory.h"
#include "tests/support/test_size.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

using test::read_text_file;
using test::run_command;

// Root in CI containers; --oversubscribe since the machine may have fewer cores than ranks.
const std::string kMpirun = SNEE_MPIEXEC;
const std::vector<std::string> kMpirunOptions = {"--allow-run-as-root", "--oversubscribe"};

// The snee-mpi processes mpirun started (its children).
std::vector<pid_t> ranks_of(pid_t mpirun) {
  std::vector<pid_t> ranks;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string stat = read_text_file(entry.path() / "stat");
    const size_t name_end = stat.rfind(')');
    if (name_end == std::string::npos || stat.find("(snee-mpi)") == std::string::npos) continue;
    std::istringstream fields(stat.substr(name_end + 2));
    char state = 0;
    pid_t parent = 0;
    fields >> state >> parent;
    if (parent == mpirun && state != 'Z') ranks.push_back(std::stoi(entry.path().filename()));
  }
  return ranks;
}

// Whether `pid` has a handler for `signal` (/proc/PID/status SigCgt): the render has started.
bool catches(pid_t pid, int signal) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.starts_with("SigCgt:"))
      return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1;
  }
  return false;
}

// Two ranks of `snee-mpi render` with `options`, started in the background, once both are
// rendering (their SIGTERM handlers are installed).
struct TwoRanks {
  TwoRanks(const fs::path& dir, const std::vector<std::string>& options)
      : run(arguments(options), dir / "log.txt") {
    ready = test::wait_for([&] {
      ranks = ranks_of(run.pid());
      if (ranks.size() != 2) return false;
      for (const pid_t r : ranks)
        if (!catches(r, SIGTERM)) return false;
      return true;
    });
  }
  ~TwoRanks() {
    for (const pid_t r : ranks) kill(r, SIGKILL);  // a rank left stopped, if any
  }
  static std::vector<std::string> arguments(const std::vector<std::string>& options) {
    std::vector<std::string> a = {kMpirun};
    a.insert(a.end(), kMpirunOptions.begin(), kMpirunOptions.end());
    a.insert(a.end(), {"-np", "2", SNEE_MPI_BINARY, "render", "builtin:default", "--resolution",
                       "32x24", "--threads", "1", "--quiet"});
    a.insert(a.end(), options.begin(), options.end());
    return a;
  }

  test::BackgroundCommand run;
  std::vector<pid_t> ranks;
  bool ready = false;
};

class MpiSignals : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("mpi"); }
  void TearDown() override { fs::remove_all(dir_); }
  // Two ranks rendering far more samples than they will get to, writing the image and stats.
  TwoRanks long_render() const {
    return TwoRanks(dir_, {"--spp", "1000000", "-o", exr(), "--stats", stats()});
  }
  std::string exr() const { return (dir_ / "m.exr").string(); }
  std::string stats() const { return (dir_ / "m.json").string(); }
  // What a stopped render leaves: the image so far, and stats that say it is incomplete.
  void expect_the_image_so_far() const {
    const Film film = read_exr(exr());
    EXPECT_LT(film.meta.min_spp, 1000000);
    EXPECT_EQ(nlohmann::json::parse(read_text_file(stats()))["complete"], false);
  }
  fs::path dir_;
};

// SIGTERM to one rank (as a batch system's time limit sends): every rank stops, the image so
// far is written, and the exit code is 143 rather than 0 for an incomplete image.
TEST_F(MpiSignals, ASignalToOneRankStopsThemAllWithItsExitCode) {
  TwoRanks two = long_render();
  ASSERT_TRUE(two.ready) << two.run.output();
  ASSERT_EQ(kill(two.ranks.back(), SIGTERM), 0);
  EXPECT_EQ(two.run.wait(std::chrono::seconds(120)), 128 + SIGTERM) << two.run.output();
  expect_the_image_so_far();
}

// Ctrl-C to mpirun itself (the terminal's SIGINT reaching mpirun): Open MPI answers with SIGTERM
// to every rank, which write the image so far, and reports 1 as the job's exit code whatever the
// ranks return (docs/reliability.md, "Signals"). The image is kept and the job fails.
TEST_F(MpiSignals, CtrlCToMpirunWritesTheImageSoFarAndFailsTheJob) {
  TwoRanks two = long_render();
  ASSERT_TRUE(two.ready) << two.run.output();
  ASSERT_EQ(kill(two.run.pid(), SIGINT), 0);
  const int code = two.run.wait(std::chrono::seconds(120));
  EXPECT_NE(code, -1) << "mpirun still waits: " << two.run.output();
  EXPECT_NE(code, 0) << two.run.output();
  expect_the_image_so_far();
}

// A rank stopped with SIGSTOP never joins: the other gives up after --join-timeout with a
// clear error, and mpirun ends the job with a non-zero exit code instead of waiting for ever.
TEST_F(MpiSignals, AStoppedRankHoldsNoOtherForEver) {
  TwoRanks two(dir_, {"--spp", std::to_string(test::sanitized_share(1000)), "--join-timeout", "2",
                      "-o", (dir_ / "s.exr").string()});
  ASSERT_TRUE(two.ready) << two.run.output();
  ASSERT_EQ(kill(two.ranks.back(), SIGSTOP), 0);
  const int code = two.run.wait(std::chrono::seconds(300));
  EXPECT_NE(code, -1) << "mpirun still waits: " << two.run.output();
  EXPECT_NE(code, 0) << two.run.output();
  EXPECT_NE(two.run.output().find("the other processes did not"), std::string::npos)
      << two.run.output();
}

// Every rank keeps its own state beside the EXR (FILE.exr.checkpoint.R-of-N, docs/resume.md):
// after one rank is killed with SIGKILL, which ends the job, the render resumed under as many
// ranks writes the image the single-process uninterrupted render writes.
TEST_F(MpiSignals, AKilledJobResumesToTheSingleProcessImage) {
  const std::string exr = (dir_ / "k.exr").string();
  const std::string spp = std::to_string(test::sanitized_share(800));
  const std::string common =
      " render builtin:default --resolution 32x24 --spp " + spp + " --quiet ";
  {
    TwoRanks two(dir_, {"--spp", spp, "--checkpoint", "0.05", "-o", exr});
    ASSERT_TRUE(two.ready) << two.run.output();
    ASSERT_TRUE(test::wait_for([&] {
      return fs::exists(exr + ".checkpoint.0-of-2") && fs::exists(exr + ".checkpoint.1-of-2");
    })) << two.run.output();
    ASSERT_EQ(kill(two.ranks.front(), SIGKILL), 0);
    EXPECT_NE(two.run.wait(std::chrono::seconds(120)), 0) << two.run.output();
  }
  const std::string mpirun = "'" + kMpirun + "' --allow-run-as-root --oversubscribe -np 2 ";
  ASSERT_EQ(
      run_command(mpirun + "'" SNEE_MPI_BINARY "'" + common + "--threads 1 --resume '" + exr + "'",
                  dir_ / "resume.txt"),
      0)
      << read_text_file(dir_ / "resume.txt");
  const std::string one = (dir_ / "one.exr").string();
  ASSERT_EQ(
      run_command("'" SNEE_BINARY "'" + common + "--threads 2 -o '" + one + "'", dir_ / "one.txt"),
      0)
      << read_text_file(dir_ / "one.txt");
  EXPECT_TRUE(test::bitwise_identical(read_exr(one), read_exr(exr)));
}

TEST(MpiCli, NonFiniteJoinTimeoutIsRejected) {
  const fs::path log = fs::temp_directory_path() / "snee_mpi_join_timeout.txt";
  for (const char* value : {"nan", "inf"}) {
    EXPECT_NE(run_command("'" SNEE_MPI_BINARY "' render --join-timeout " + std::string(value), log),
              0);
    EXPECT_NE(read_text_file(log).find("expected a finite number"), std::string::npos)
        << read_text_file(log);
  }
  fs::remove(log);
}

class MpiRender : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("mpi_render"); }
  void TearDown() override { fs::remove_all(dir_); }

  // `snee render ARGS` with 2 threads, and `snee-mpi render ARGS MPI_OPTIONS` with one rank per
  // entry of `threads`, each with that many threads (Open MPI's MPMD form, "-np 1 ... : -np 1
  // ..."). Expects both to succeed with bitwise the same image; returns the split render's stats.
  nlohmann::json render_both(const std::string& args, const std::vector<int>& threads,
                             const std::string& mpi_options) {
    const std::string one = (dir_ / "one.exr").string(), mpi = (dir_ / "mpi.exr").string();
    EXPECT_EQ(run_command("'" SNEE_BINARY "' render" + args + " --threads 2 -o '" + one + "'",
                          dir_ / "one.txt"),
              0)
        << read_text_file(dir_ / "one.txt");
    std::string command = "'" + kMpirun + "' --allow-run-as-root --oversubscribe";
    for (size_t r = 0; r < threads.size(); ++r) {
      command += std::string(r > 0 ? " :" : "") + " -np 1 '" SNEE_MPI_BINARY "' render" + args +
                 " " + mpi_options + " --threads " + std::to_string(threads[r]) + " -o '" + mpi +
                 "' --stats '" + (dir_ / "mpi.json").string() + "'";
    }
    EXPECT_EQ(run_command(command, dir_ / "mpi.txt"), 0) << read_text_file(dir_ / "mpi.txt");
    EXPECT_TRUE(test::bitwise_identical(read_exr(one), read_exr(mpi))) << mpi_options;
    return nlohmann::json::parse(read_text_file(dir_ / "mpi.json"));
  }
  fs::path dir_;
};

TEST_F(MpiRender, ThreeRanksRenderTheSingleProcessImageWithEitherSplit) {
  const std::string args =
      " builtin:bunny-cone-r0.04 --integrator snee --resolution 40x24 --spp 4 --quiet";
  for (const char* split : {"static", "dynamic"}) {
    const auto stats = render_both(args, {1, 1, 1}, std::string("--split ") + split);
    EXPECT_EQ(stats["paths"].get<uint64_t>(), 40u * 24u * 4u) << split;
    EXPECT_EQ(stats["complete"], true) << split;
    EXPECT_EQ(stats["min_spp"], 4) << split;
    EXPECT_EQ(stats["processes"].size(), 3u) << split;
  }
}

// Ranks with different thread counts claim tiles from the shared counter as they can start
// them: every tile is rendered once, by whichever rank, and the image is still bitwise the
// single-process one (here with the default scene's noise target, which stops each tile on
// its own samples). The faster rank's larger share is not asserted: it is timing.
TEST_F(MpiRender, RanksWithDifferentThreadCountsShareTheTilesOut) {
  const std::string args =
      " builtin:default --resolution 64x48 --tile-size 8 --spp 32 --quiet";  // 48 tiles
  for (const std::vector<int>& threads : {std::vector<int>{2, 1}, std::vector<int>{2, 1, 1}}) {
    const auto stats = render_both(args, threads, "");
    ASSERT_EQ(stats["processes"].size(), threads.size());
    uint64_t tiles = 0;
    for (size_t r = 0; r < threads.size(); ++r) {
      const auto& process = stats["processes"][r];
      EXPECT_EQ(process["threads"], threads[r]);
      EXPECT_GE(process["tiles"].get<uint64_t>(), 1u) << "rank " << r << ": " << stats.dump();
      EXPECT_GT(process["busy_seconds"].get<double>(), 0);
      EXPECT_GE(process["join_seconds"].get<double>(), 0);
      tiles += process["tiles"].get<uint64_t>();
    }
    EXPECT_EQ(tiles, 48u) << stats.dump();
    EXPECT_EQ(stats["complete"], true);
  }
}

// A checkpoint holds a fixed set of tiles, which claimed tiles are not.
TEST(MpiCli, DynamicSplitWithCheckpointIsRejected) {
  const fs::path log = fs::temp_directory_path() / "snee_mpi_dynamic_checkpoint.txt";
  EXPECT_NE(run_command("'" + kMpirun + "' --allow-run-as-root --oversubscribe -np 2 '" +
                            SNEE_MPI_BINARY +
                            "' render --resolution 8x8 --spp 1 --quiet --split dynamic "
                            "--checkpoint 1 -o '" +
                            (fs::temp_directory_path() / "snee_mpi_dc.exr").string() + "'",
                        log),
            0);
  EXPECT_NE(read_text_file(log).find("--checkpoint and --resume need the static split"),
            std::string::npos)
      << read_text_file(log);
  fs::remove(log);
}

}  // namespace
}  // namespace snee
