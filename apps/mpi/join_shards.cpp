#include "apps/mpi/join_shards.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "apps/mpi/mpi_wait.h"

namespace snee {
namespace {

static_assert(sizeof(Rgb) == 3 * sizeof(float));

// Non-blocking, so the join can give up on a process that never comes (mpi_wait.h).
class Reductions {
 public:
  Reductions(int rank, MPI_Comm comm) : rank_(rank), comm_(comm) {}
  void reduce_in_place(void* values, int count, MPI_Datatype type, MPI_Op op) {
    requests_.emplace_back();
    if (rank_ == 0) {
      MPI_Ireduce(MPI_IN_PLACE, values, count, type, op, 0, comm_, &requests_.back());
    } else {
      MPI_Ireduce(values, nullptr, count, type, op, 0, comm_, &requests_.back());
    }
  }
  void all_reduce_in_place(void* values, int count, MPI_Datatype type, MPI_Op op) {
    requests_.emplace_back();
    MPI_Iallreduce(MPI_IN_PLACE, values, count, type, op, comm_, &requests_.back());
  }
  void gather_to_root(const double* values, int count, double* all) {
    requests_.emplace_back();
    MPI_Igather(values, count, MPI_DOUBLE, all, count, MPI_DOUBLE, 0, comm_, &requests_.back());
  }
  void wait(double seconds) {
    wait_or_abort(requests_, seconds, "join the render", comm_);
    requests_.clear();
  }

 private:
  const int rank_;
  const MPI_Comm comm_;
  std::vector<MPI_Request> requests_;
};

}  // namespace

bool join_shards(RenderResult& result, int& exit_status, double timeout_seconds, MPI_Comm comm) {
  const auto arrived = std::chrono::steady_clock::now();
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  Reductions join(rank, comm);
  // An Rgb is three packed floats, so each film plane reduces as one float array.
  // The AOV planes are empty unless the render keeps them (so they reduce nothing).
  for (std::vector<Rgb>* plane :
       {&result.film.mean, &result.film.variance_of_mean, &result.film.albedo, &result.film.normal})
    join.reduce_in_place(plane->data(), static_cast<int>(3 * plane->size()), MPI_FLOAT, MPI_SUM);
  join.reduce_in_place(result.film.depth.data(), static_cast<int>(result.film.depth.size()),
                       MPI_FLOAT, MPI_SUM);
  join.reduce_in_place(result.film.pixel_spp.data(), static_cast<int>(result.film.pixel_spp.size()),
                       MPI_UINT32_T, MPI_SUM);
  // Zero for every tile another process ran, so the sum is each tile's own cost.
  join.reduce_in_place(result.stats.tile_seconds.data(),
                       static_cast<int>(result.stats.tile_seconds.size()), MPI_DOUBLE, MPI_SUM);

  RenderStats& s = result.stats;
  std::vector<uint64_t> counts(s.rays.begin(), s.rays.end());
  counts.push_back(s.paths);
  counts.push_back(s.nonfinite_samples);
  join.reduce_in_place(counts.data(), static_cast<int>(counts.size()), MPI_UINT64_T, MPI_SUM);
  double times[2] = {s.seconds, s.sampling_seconds};
  join.reduce_in_place(times, 2, MPI_DOUBLE, MPI_MAX);
  join.reduce_in_place(&s.sampling_cpu_seconds, 1, MPI_DOUBLE, MPI_SUM);
  join.reduce_in_place(s.stage_seconds.data(), static_cast<int>(s.stage_seconds.size()), MPI_DOUBLE,
                       MPI_SUM);
  int complete = result.complete ? 1 : 0;
  join.reduce_in_place(&complete, 1, MPI_INT, MPI_MIN);
  join.all_reduce_in_place(&exit_status, 1, MPI_INT, MPI_MAX);
  join.wait(timeout_seconds);

  // The reductions complete once the last process has arrived: this process waited since
  // `arrived` for the others (and for the transfer, small beside a render).
  const double share[4] = {
      static_cast<double>(s.threads), static_cast<double>(s.tiles_rendered), s.sampling_seconds,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - arrived).count()};
  std::vector<double> shares(rank == 0 ? 4 * static_cast<size_t>(ranks) : 0);
  join.gather_to_root(share, 4, shares.data());
  join.wait(timeout_seconds);
  if (rank != 0) return false;

  for (int r = 0; r < ranks; ++r) {
    const double* p = &shares[4 * static_cast<size_t>(r)];
    s.processes.push_back({static_cast<int>(p[0]), static_cast<uint64_t>(p[1]), p[2], p[3]});
  }
  for (size_t k = 0; k < s.rays.size(); ++k) s.rays[k] = counts[k];
  s.paths = counts[s.rays.size()];
  s.nonfinite_samples = counts[s.rays.size() + 1];
  s.seconds = times[0];
  s.sampling_seconds = times[1];
  result.film.meta.render_seconds = s.seconds;
  result.film.meta.nonfinite_samples = s.nonfinite_samples;
  // Each pixel's count is its tile's, so the fewest over the pixels is the fewest over the
  // tiles, however the tiles were shared out.
  const auto& spp = result.film.pixel_spp;
  if (!spp.empty())
    result.film.meta.min_spp = static_cast<int>(*std::min_element(spp.begin(), spp.end()));
  result.complete = complete == 1;
  return true;
}

}  // namespace snee
