// snee-mpi: `snee render` split across MPI processes, e.g.
//   mpirun -np 4 snee-mpi render SCENE --spp 4096 --threads 16
// Every rank loads the scene and renders, with its own threads, the tiles it claims from a
// shared counter while it renders (--split dynamic), or those whose raster index is its rank
// modulo the number of ranks (--split static); rank 0 gathers the pixels and writes the files.
// The image is bitwise the one `snee render` makes.
#include <mpi.h>

#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/error_exit.h"
#include "apps/mpi/claim_latency.h"
#include "apps/mpi/join_shards.h"
#include "apps/mpi/mpi_wait.h"
#include "apps/mpi/stop_together.h"
#include "apps/mpi/tile_counter.h"
#include "apps/option_checks.h"
#include "apps/render_command.h"
#include "apps/simd_option.h"

namespace {

// Without --join-timeout, a rank waits for the others as long again as its own render took
// (claimed tiles end together, and static shards are interleaved tiles, so their costs are
// close) plus this margin.
constexpr double kJoinMarginSeconds = 60;

// Tiles per claim. A claim costs one MPI_Fetch_and_op round trip, a few microseconds on one
// host and tens over a network (docs/performance.md, "Several processes"), while a tile of
// 16x16 pixels takes milliseconds even at a few spp: claiming one at a time costs well under
// 1% and leaves the finest grain for the end of the render, where the balance is decided.
constexpr uint64_t kTilesPerClaim = 1;

}  // namespace

int main(int argc, char** argv) {
  // Render threads ask StopTogether whether to stop, one at a time.
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);

  CLI::App app("snee-mpi: snee render split across MPI processes", "snee-mpi");
  app.set_version_flag("--version", snee::version_text);
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "error: " + std::string(e.what()) + "\nrun 'snee-mpi render --help'\n";
  });
  const snee::RenderCommand render(app);
  double join_timeout = 0;
  app.get_subcommand("render")
      ->add_option("--join-timeout", join_timeout,
                   "Seconds a process that has finished its tiles waits for the others before "
                   "ending them all with an error (0: as long as its own render took + 60 s)")
      ->check(snee::finite_at_least(0))
      ->capture_default_str();
  std::string split = "dynamic";
  CLI::Option* split_option =
      app.get_subcommand("render")
          ->add_option("--split", split,
                       "How the processes share the tiles: dynamic (each claims the next tile "
                       "from a counter on rank 0 whenever it can start one, so uneven processes "
                       "finish together) or static (rank R renders the tiles whose raster index "
                       "is R modulo the number of processes). --checkpoint and --resume need "
                       "static, and make it the default (docs/resume.md)")
          ->check(CLI::IsMember({"static", "dynamic"}))
          ->default_str("dynamic");
  CLI::App* latency = app.add_subcommand(
      "claim-latency",
      "Time the tile claims of --split dynamic (MPI_Fetch_and_op to rank 0) from every other "
      "rank while rank 0 computes (docs/performance.md)");
  int claims = 2000;
  double busy_seconds = 2;
  latency->add_option("--claims", claims, "Claims each rank makes")
      ->check(snee::integer_at_least(1))
      ->capture_default_str();
  latency->add_option("--busy-seconds", busy_seconds, "Seconds rank 0 computes meanwhile")
      ->check(snee::finite_at_least(0))
      ->capture_default_str();
  int code = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same arguments; only rank 0 prints help or the error.
    code = rank == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : e.get_exit_code());
    MPI_Finalize();
    return code;
  }
  if (latency->parsed()) {
    code = ranks > 1 ? snee::measure_claim_latency(MPI_COMM_WORLD, claims, busy_seconds) : 2;
    if (code != 0 && rank == 0) std::fprintf(stderr, "error: claim-latency needs two processes\n");
    MPI_Finalize();
    return code;
  }
  CLI::App& command = *app.get_subcommand("render");
  const bool keeps_state = command.count("--checkpoint") > 0 || command.count("--resume") > 0;
  if (keeps_state && split_option->count() == 0) split = "static";
  snee::RenderDistribution distribution;
  distribution.shard = rank;
  distribution.shard_count = ranks;
  // Every MPI call of the render threads (claims, StopTogether's polls) is made under it.
  std::mutex mpi_mutex;
  std::optional<snee::TileCounter> counter;
  // Claims are made from render threads; without thread support the split stays static. An
  // explicit --split dynamic with --checkpoint or --resume gets the render's error naming them.
  if (split == "dynamic" && provided >= MPI_THREAD_SERIALIZED) {
    counter.emplace(MPI_COMM_WORLD, mpi_mutex, kTilesPerClaim);
    distribution.tile_source = [&] { return counter->claim(); };
  }
  // Without thread support the processes still join, they just do not stop together.
  std::optional<snee::StopTogether> stop_together;
  if (provided >= MPI_THREAD_SERIALIZED) {
    stop_together.emplace(MPI_COMM_WORLD, mpi_mutex);
    distribution.stop_together = [&](int status) { return (*stop_together)(status); };
  }
  distribution.join = [&](snee::RenderResult& r, int& status) {
    const double timeout = join_timeout > 0 ? join_timeout : r.stats.seconds + kJoinMarginSeconds;
    return snee::join_shards(r, status, timeout, MPI_COMM_WORLD);
  };
  code = snee::run_reporting_errors([&] { return render.run(distribution); });
  stop_together.reset();
  // MPI_Finalize waits for every process, so one stopped after the join would hold the
  // others there for ever: they meet once more, with a deadline, first.
  if (code == 0 || code >= 128) {
    std::vector<MPI_Request> finished(1);
    MPI_Ibarrier(MPI_COMM_WORLD, finished.data());
    snee::wait_or_abort(finished, join_timeout > 0 ? join_timeout : kJoinMarginSeconds, "finish",
                        MPI_COMM_WORLD);
  }
  // A rank that failed before the join would leave the others waiting in it for ever.
  if (code != 0 && code < 128) MPI_Abort(MPI_COMM_WORLD, code);
  counter.reset();  // collective: every process is past its claims, they met above
  MPI_Finalize();
  return code;
}
