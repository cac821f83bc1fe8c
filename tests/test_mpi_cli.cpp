// snee-mpi under mpirun: three processes on disjoint tiles give the image `snee render` gives,
// bit for bit, and the merged statistics count every path once.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/film.h"
#include "tests/support/command_line.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

using test::read_text_file;
using test::run_command;

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
  // Root in CI containers; --oversubscribe since the machine may have fewer cores than ranks.
  const std::string mpirun = "'" SNEE_MPIEXEC "' --allow-run-as-root --oversubscribe -np 3 ";
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
