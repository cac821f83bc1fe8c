// snee-mpi under mpirun: three processes on disjoint tiles give the image `snee render` gives,
// bit for bit, and the merged statistics count every path once; a signal to one process stops
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
  fs::path dir_;
};

// SIGTERM to one rank (as a batch system's time limit sends): every rank stops, the image so
// far is written, and the exit code is 143 rather than 0 for an incomplete image.
TEST_F(MpiSignals, ASignalToOneRankStopsThemAllWithItsExitCode) {
  const std::string exr = (dir_ / "m.exr").string();
  const std::string stats = (dir_ / "m.json").string();
  TwoRanks two(dir_, {"--spp", "1000000", "-o", exr, "--stats", stats});
  ASSERT_TRUE(two.ready) << two.run.output();
  ASSERT_EQ(kill(two.ranks.back(), SIGTERM), 0);
  EXPECT_EQ(two.run.wait(std::chrono::seconds(120)), 128 + SIGTERM) << two.run.output();
  const Film film = read_exr(exr);
  EXPECT_LT(film.meta.min_spp, 1000000);
  EXPECT_EQ(nlohmann::json::parse(read_text_file(stats))["complete"], false);
}

// A rank stopped with SIGSTOP never joins: the other gives up after --join-timeout with a
// clear error, and mpirun ends the job with a non-zero exit code instead of waiting for ever.
TEST_F(MpiSignals, AStoppedRankHoldsNoOtherForEver) {
  TwoRanks two(dir_, {"--spp", "1000", "--join-timeout", "2", "-o", (dir_ / "s.exr").string()});
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
  const std::string common = " render builtin:default --resolution 32x24 --spp 800 --quiet ";
  {
    TwoRanks two(dir_, {"--spp", "800", "--checkpoint", "0.05", "-o", exr});
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

TEST(MpiCli, ThreeRanksRenderTheSingleProcessImage) {
  const fs::path dir = fs::temp_directory_path() / "snee_mpi_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string args =
      " render builtin:bunny-cone-r0.04 --integrator snee --resolution 40x24 --spp 4 "
      "--threads 1 --quiet";
  ASSERT_EQ(run_command("'" SNEE_BINARY "'" + args + " -o '" + (dir / "one.exr").string() + "'",
                        dir / "one.txt"),
            0)
      << read_text_file(dir / "one.txt");
  const std::string mpirun = "'" + kMpirun + "' --allow-run-as-root --oversubscribe -np 3 ";
  ASSERT_EQ(
      run_command(mpirun + "'" SNEE_MPI_BINARY "'" + args + " -o '" + (dir / "mpi.exr").string() +
                      "' --stats '" + (dir / "mpi.json").string() + "'",
                  dir / "mpi.txt"),
      0)
      << read_text_file(dir / "mpi.txt");
  const Film one = read_exr((dir / "one.exr").string());
  const Film mpi = read_exr((dir / "mpi.exr").string());
  EXPECT_TRUE(test::bitwise_identical(one, mpi));
  EXPECT_EQ(mpi.meta.spp, 4);
  EXPECT_EQ(mpi.meta.min_spp, 4);
  const auto stats = nlohmann::json::parse(read_text_file(dir / "mpi.json"));
  EXPECT_EQ(stats["paths"].get<uint64_t>(), 40u * 24u * 4u);
  EXPECT_EQ(stats["complete"], true);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snee
