#include "apps/mpi/join_shards.h"

#include <cstdint>
#include <vector>

namespace snee {
namespace {

static_assert(sizeof(Rgb) == 3 * sizeof(float));

void reduce_in_place(void* values, int count, MPI_Datatype type, MPI_Op op, int rank,
                     MPI_Comm comm) {
  if (rank == 0) {
    MPI_Reduce(MPI_IN_PLACE, values, count, type, op, 0, comm);
  } else {
    MPI_Reduce(values, nullptr, count, type, op, 0, comm);
  }
}

}  // namespace

bool join_shards(RenderResult& result, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // An Rgb is three packed floats, so each film plane reduces as one float array.
  for (std::vector<Rgb>* plane : {&result.film.mean, &result.film.variance_of_mean}) {
    reduce_in_place(plane->data(), static_cast<int>(3 * plane->size()), MPI_FLOAT, MPI_SUM, rank,
                    comm);
  }

  RenderStats& s = result.stats;
  std::vector<uint64_t> counts(s.rays.begin(), s.rays.end());
  counts.push_back(s.paths);
  counts.push_back(s.nonfinite_samples);
  reduce_in_place(counts.data(), static_cast<int>(counts.size()), MPI_UINT64_T, MPI_SUM, rank,
                  comm);
  double times[2] = {s.seconds, s.sampling_seconds};
  reduce_in_place(times, 2, MPI_DOUBLE, MPI_MAX, rank, comm);
  reduce_in_place(&s.sampling_cpu_seconds, 1, MPI_DOUBLE, MPI_SUM, rank, comm);
  reduce_in_place(s.stage_seconds.data(), static_cast<int>(s.stage_seconds.size()), MPI_DOUBLE,
                  MPI_SUM, rank, comm);
  int least[2] = {result.film.meta.min_spp, result.complete ? 1 : 0};
  reduce_in_place(least, 2, MPI_INT, MPI_MIN, rank, comm);
  if (rank != 0) return false;

  for (size_t k = 0; k < s.rays.size(); ++k) s.rays[k] = counts[k];
  s.paths = counts[s.rays.size()];
  s.nonfinite_samples = counts[s.rays.size() + 1];
  s.seconds = times[0];
  s.sampling_seconds = times[1];
  result.film.meta.render_seconds = s.seconds;
  result.film.meta.nonfinite_samples = s.nonfinite_samples;
  result.film.meta.min_spp = least[0];
  result.complete = least[1] == 1;
  return true;
}

}  // namespace snee
