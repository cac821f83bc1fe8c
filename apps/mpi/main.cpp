// snee-mpi: `snee render` split across MPI processes, e.g.
//   mpirun -np 4 snee-mpi render SCENE --spp 4096 --threads 16
// Every rank loads the scene and renders the tiles whose raster index is its rank modulo the
// number of ranks, with its own threads; rank 0 gathers the pixels and writes the files. The
// image is bitwise the one `snee render` makes.
#include <mpi.h>

#include <string>

#include <CLI/CLI.hpp>

#include "apps/error_exit.h"
#include "apps/mpi/join_shards.h"
#include "apps/render_command.h"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);

  CLI::App app("snee-mpi: snee render split across MPI processes", "snee-mpi");
  app.set_version_flag("--version", "snee " SNEE_VERSION);
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "error: " + std::string(e.what()) + "\nrun 'snee-mpi render --help'\n";
  });
  const snee::RenderCommand render(app);
  int code = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same arguments; only rank 0 prints help or the error.
    code = rank == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : e.get_exit_code());
    MPI_Finalize();
    return code;
  }
  snee::RenderDistribution distribution;
  distribution.shard = rank;
  distribution.shard_count = ranks;
  distribution.join = [](snee::RenderResult& r) { return snee::join_shards(r, MPI_COMM_WORLD); };
  code = snee::run_reporting_errors([&] { return render.run(distribution); });
  // A rank that failed before the join would leave the others waiting in it for ever.
  if (code != 0 && code < 128) MPI_Abort(MPI_COMM_WORLD, code);
  MPI_Finalize();
  return code;
}
