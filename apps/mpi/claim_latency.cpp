#include "apps/mpi/claim_latency.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <numeric>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/mpi/tile_counter.h"

namespace snee {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kFigures = 4;  // median, mean, 90th percentile, largest

// Rank 0's render threads: arithmetic only, no MPI call, for `seconds`.
void spin(double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  volatile double x = 1;
  while (Clock::now() < end) {
    for (int i = 0; i < 1000; ++i) x = x * 1.0000001 + 1e-9;
  }
}

}  // namespace

int measure_claim_latency(MPI_Comm comm, int claims, double busy_seconds) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::mutex mpi_mutex;
  std::vector<double> figures(kFigures, 0.0);
  {
    TileCounter counter(comm, mpi_mutex, 1);
    if (rank == 0) {
      spin(busy_seconds);
    } else {
      std::vector<double> micros(static_cast<size_t>(claims));
      for (double& m : micros) {
        const auto start = Clock::now();
        counter.claim();
        m = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
      }
      std::sort(micros.begin(), micros.end());
      figures = {micros[micros.size() / 2],
                 std::accumulate(micros.begin(), micros.end(), 0.0) / micros.size(),
                 micros[micros.size() * 9 / 10], micros.back()};
    }
    MPI_Barrier(comm);  // every claim is done before the window goes
  }
  std::vector<double> all(rank == 0 ? kFigures * static_cast<size_t>(ranks) : 0);
  MPI_Gather(figures.data(), kFigures, MPI_DOUBLE, all.data(), kFigures, MPI_DOUBLE, 0, comm);
  if (rank != 0) return 0;
  nlohmann::ordered_json json = {
      {"ranks", ranks}, {"claims_per_rank", claims}, {"rank0_busy_seconds", busy_seconds}};
  nlohmann::ordered_json per_rank = nlohmann::ordered_json::array();
  for (int r = 1; r < ranks; ++r) {
    const double* f = &all[kFigures * static_cast<size_t>(r)];
    per_rank.push_back(
        {{"rank", r}, {"median_us", f[0]}, {"mean_us", f[1]}, {"p90_us", f[2]}, {"max_us", f[3]}});
  }
  json["claim_latency"] = per_rank;
  std::printf("%s\n", json.dump(2).c_str());
  return 0;
}

}  // namespace snee
