#include "apps/bench_report.h"

#include <array>
#include <optional>

#include "apps/stats_json.h"

namespace snee {

namespace {

constexpr int kStages = static_cast<int>(Stage::kCount);

// The raw query that bounds each ray kind: camera rays are primary rays; extension rays and
// SNEE probes are closest-hit queries from inside the medium with tfar = inf; shadow segments
// are mostly occlusion queries. Single-ray rates, the limit a path-at-a-time renderer has.
RawQuery limit_of(RayKind k) {
  switch (k) {
    case RayKind::kCamera:
      return RawQuery::kCameraSingle;
    case RayKind::kShadow:
      return RawQuery::kOcclusionSingle;
    default:
      return RawQuery::kClosestSingle;
  }
}

struct Figures {
  double seconds = 0, cpu_seconds = 0, cpu_share = 0;
  double paths_per_second = 0, paths_per_cpu_second = 0;
  std::array<double, kRayKinds + 1> mrays{}, mrays_cpu{};  // by kind, then total
  double vs_closest_single = 0;  // total rays per CPU-second / raw closest-hit single-ray rate
  double traversal_bound = 0;    // CPU time raw traversal of these rays takes / CPU time taken
  std::array<double, kStages> stage_share{};  // of thread time (threads x wall clock)
  // Thread time outside every stage, when the stages' sum leaves some. Stage times are sampled
  // on one turn in timing_period and scaled up (scheduler/work_unit.cpp), so their sum can
  // exceed the thread time; then the rest is unknown and stage_excess says by how much.
  std::optional<double> other_share;
  double stage_excess = 0;
  MeasurementCheck check;
  double extend_batch = 0;  // mean rays per extend stage call
};

Figures figures(const BenchRun& run, const EmbreeThroughput& raw) {
  const RenderStats& s = run.measurement.median();
  Figures f;
  f.seconds = s.sampling_seconds;
  f.cpu_seconds = s.sampling_cpu_seconds;
  f.check = check_measurement(f.seconds, f.cpu_seconds, run.threads);
  f.cpu_share = f.check.cpu_share;
  auto per = [](double count, double seconds) { return seconds > 0 ? count / seconds : 0; };
  f.paths_per_second = per(static_cast<double>(s.paths), f.seconds);
  f.paths_per_cpu_second = per(static_cast<double>(s.paths), f.cpu_seconds);
  double bound_seconds = 0;
  for (int k = 0; k <= kRayKinds; ++k) {
    const double rays =
        static_cast<double>(k < kRayKinds ? s.rays[static_cast<size_t>(k)] : s.total_rays());
    f.mrays[k] = per(rays, f.seconds) * 1e-6;
    f.mrays_cpu[k] = per(rays, f.cpu_seconds) * 1e-6;
    if (k == kRayKinds) break;
    const double limit = raw[limit_of(static_cast<RayKind>(k))].mrays_per_cpu_second;
    if (limit > 0) bound_seconds += rays * 1e-6 / limit;
  }
  const double closest = raw[RawQuery::kClosestSingle].mrays_per_cpu_second;
  f.vs_closest_single = closest > 0 ? f.mrays_cpu[kRayKinds] / closest : 0;
  f.traversal_bound = per(bound_seconds, f.cpu_seconds);
  const double thread_seconds = f.seconds * run.threads;
  double staged = 0;
  for (int i = 0; i < kStages; ++i) {
    f.stage_share[i] = per(s.stage_seconds[i], thread_seconds);
    staged += f.stage_share[i];
  }
  if (staged <= 1)
    f.other_share = 1 - staged;
  else
    f.stage_excess = staged - 1;
  const uint64_t extend_calls = s.stage_calls[static_cast<int>(Stage::kExtend)];
  f.extend_batch = extend_calls > 0 ? static_cast<double>(s.rays[0] + s.rays[1]) /
                                          static_cast<double>(extend_calls)
                                    : 0;
  return f;
}

// The run of a schedule and thread count at a SIMD level (any, without --simd: each schedule
// ran at one level).
const BenchRun* find_run(const BenchResult& r, const std::string& schedule, int threads,
                         SimdLevel simd) {
  for (const BenchRun& run : r.runs) {
    if (run.schedule == schedule && run.threads == threads &&
        (run.simd == simd || r.simd_levels.empty()))
      return &run;
  }
  return nullptr;
}

// Paths per second of `schedule` over the megakernel's at the same thread count (wall clock
// and CPU time); 0 when either is missing.
std::array<double, 2> vs_megakernel(const BenchResult& r, const BenchRun& run) {
  const BenchRun* mega = find_run(r, "megakernel", run.threads, run.simd);
  if (!mega) return {0, 0};
  const Figures a = figures(run, r.raw), b = figures(*mega, r.raw);
  return {b.paths_per_second > 0 ? a.paths_per_second / b.paths_per_second : 0,
          b.paths_per_cpu_second > 0 ? a.paths_per_cpu_second / b.paths_per_cpu_second : 0};
}

// Paths per CPU-second of a run over the same schedule's at the same thread count with the first
// SIMD level measured: the speed-up of a wider SIMD level; 1 without --simd, 0 when that run is
// missing.
double vs_first_simd_level(const BenchResult& r, const BenchRun& run) {
  if (r.simd_levels.empty()) return 1;
  const BenchRun* first = find_run(r, run.schedule, run.threads, r.simd_levels[0]);
  if (!first) return 0;
  const double base = figures(*first, r.raw).paths_per_cpu_second;
  return base > 0 ? figures(run, r.raw).paths_per_cpu_second / base : 0;
}

nlohmann::ordered_json by_kind(const std::array<double, kRayKinds + 1>& v) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (int k = 0; k < kRayKinds; ++k) j[ray_kind_name(static_cast<RayKind>(k))] = v[k];
  j["total"] = v[kRayKinds];
  return j;
}

}  // namespace

void print_bench_result(std::FILE* out, const BenchResult& r) {
  const BenchWorkload& w = *r.workload;
  const Camera& c = w.scene.camera;
  std::fprintf(
      out, "\n== %s: %s\n   %s, %zu triangles, %dx%d, %d spp, %llu paths\n", w.name.c_str(),
      w.description.c_str(), w.source.c_str(), r.triangles, c.width, c.height, r.spp,
      r.runs.empty() ? 0ull
                     : static_cast<unsigned long long>(r.runs[0].measurement.median().paths));
  std::fprintf(out, "   raw Embree, 1 thread, Mrays per CPU-second:");
  for (int q = 0; q < static_cast<int>(RawQuery::kCount); ++q)
    std::fprintf(out, " %s %.2f", raw_query_name(static_cast<RawQuery>(q)),
                 r.raw.rate[q].mrays_per_cpu_second);
  std::fprintf(out, "\n");
  if (!r.runs.empty()) {
    const RenderStats& s = r.runs[0].measurement.median();
    const double paths = static_cast<double>(std::max<uint64_t>(1, s.paths));
    std::fprintf(out, "   rays per path:");
    for (int k = 0; k < kRayKinds; ++k)
      std::fprintf(out, " %s %.2f", ray_kind_name(static_cast<RayKind>(k)),
                   static_cast<double>(s.rays[k]) / paths);
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "   %-10s %3s %-6s %10s %11s %7s %8s %6s %6s %6s %6s %6s %6s %7s %6s %6s %6s\n",
               "schedule", "thr", "simd", "paths/s", "paths/cpu-s", "Mrays/s", "Mr/cpu-s", "cpu%",
               "%raw1", "bound", "occup", "lanes", "batch", "RSS MiB", "xmega", "xm-cpu", "xsimd");
  for (const BenchRun& run : r.runs) {
    const Figures f = figures(run, r.raw);
    const auto ratio = vs_megakernel(r, run);
    std::fprintf(out,
                 "   %-10s %3d %-6s %10.0f %11.0f %7.2f %8.2f %5.0f%% %5.0f%% %5.0f%% %6.3f %6.3f "
                 "%6.0f %7.1f %6.2f %6.2f %6.2f\n",
                 run.schedule.c_str(), run.threads, std::string(simd_level_name(run.simd)).c_str(),
                 f.paths_per_second, f.paths_per_cpu_second, f.mrays[kRayKinds],
                 f.mrays_cpu[kRayKinds], 100 * f.cpu_share, 100 * f.vs_closest_single,
                 100 * f.traversal_bound, run.measurement.median().queue_occupancy,
                 run.measurement.median().all_simd_lanes().occupancy(), f.extend_batch,
                 run.measurement.peak_memory_mib(), ratio[0], ratio[1],
                 vs_first_simd_level(r, run));
  }
  std::fprintf(out, "   stage time, %% of thread time (threads x wall clock)\n   %-10s %3s %-6s",
               "schedule", "thr", "simd");
  for (int i = 0; i < kStages; ++i) std::fprintf(out, " %8s", stage_label(static_cast<Stage>(i)));
  std::fprintf(out, " %8s\n", "other");
  for (const BenchRun& run : r.runs) {
    const Figures f = figures(run, r.raw);
    std::fprintf(out, "   %-10s %3d %-6s", run.schedule.c_str(), run.threads,
                 std::string(simd_level_name(run.simd)).c_str());
    for (int i = 0; i < kStages; ++i) std::fprintf(out, " %7.1f%%", 100 * f.stage_share[i]);
    if (f.other_share)
      std::fprintf(out, " %7.1f%%\n", 100 * *f.other_share);
    else
      std::fprintf(out, " %8s  (stages sum to %.1f%% more than the thread time)\n", "n/a",
                   100 * f.stage_excess);
  }
  for (const BenchRun& run : r.runs) {
    for (const std::string& warning : figures(run, r.raw).check.warnings)
      std::fprintf(stderr, "warning: %s, %s, %d thread(s), %s: %s\n", w.name.c_str(),
                   run.schedule.c_str(), run.threads,
                   std::string(simd_level_name(run.simd)).c_str(), warning.c_str());
  }
}

nlohmann::ordered_json bench_result_json(const BenchResult& r) {
  const BenchWorkload& w = *r.workload;
  nlohmann::ordered_json raw = nlohmann::ordered_json::object();
  for (int q = 0; q < static_cast<int>(RawQuery::kCount); ++q) {
    raw[raw_query_name(static_cast<RawQuery>(q))] = {
        {"mrays_per_second", r.raw.rate[q].mrays_per_second},
        {"mrays_per_cpu_second", r.raw.rate[q].mrays_per_cpu_second}};
  }
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const BenchRun& run : r.runs) {
    const RenderStats& s = run.measurement.median();
    const Figures f = figures(run, r.raw);
    const auto ratio = vs_megakernel(r, run);
    nlohmann::ordered_json stages = nlohmann::ordered_json::object();
    for (int i = 0; i < kStages; ++i) {
      stages[stage_name(static_cast<Stage>(i))] = {{"seconds", s.stage_seconds[i]},
                                                   {"calls", s.stage_calls[i]},
                                                   {"share_of_thread_time", f.stage_share[i]}};
    }
    runs.push_back({
        {"schedule", run.schedule},
        {"threads", run.threads},
        {"simd_level", simd_level_name(run.simd)},
        {"vs_first_simd_level", {{"paths_per_cpu_second", vs_first_simd_level(r, run)}}},
        {"seconds", f.seconds},
        {"cpu_seconds", f.cpu_seconds},
        {"cpu_share", f.cpu_share},
        {"repeat_seconds", run.measurement.sampling_seconds()},
        {"repeat_cpu_seconds", run.measurement.sampling_cpu_seconds()},
        {"paths", s.paths},
        {"paths_per_second", f.paths_per_second},
        {"paths_per_cpu_second", f.paths_per_cpu_second},
        {"rays", ray_counts_json(s)},
        {"mrays_per_second", by_kind(f.mrays)},
        {"mrays_per_cpu_second", by_kind(f.mrays_cpu)},
        {"ratio_to_raw_embree",
         {{"total_vs_closest_single", f.vs_closest_single},
          {"traversal_bound_fraction", f.traversal_bound}}},
        {"vs_megakernel", {{"paths_per_second", ratio[0]}, {"paths_per_cpu_second", ratio[1]}}},
        {"stages", stages},
        {"other_share_of_thread_time",
         f.other_share ? nlohmann::ordered_json(*f.other_share) : nlohmann::ordered_json()},
        {"stage_excess_share_of_thread_time", f.stage_excess},
        {"warnings", f.check.warnings},
        {"queue_capacity", run.queue_capacity},
        {"queue_occupancy", s.queue_occupancy},
        {"simd", simd_lanes_json(s)},
        {"mean_extend_batch", f.extend_batch},
        {"path_state_bytes_per_slot", s.path_state_bytes_per_slot},
        {"peak_memory_mib", run.measurement.peak_memory_mib()},
    });
  }
  return {
      {"name", w.name},
      {"description", w.description},
      {"scene", w.source},
      {"integrator", w.integrator},
      {"max_depth", w.max_depth},
      {"triangles", r.triangles},
      {"resolution", {{"width", w.scene.camera.width}, {"height", w.scene.camera.height}}},
      {"spp", r.spp},
      {"raw_embree", {{"rays_per_query", r.raw.rays_per_query}, {"threads", 1}, {"queries", raw}}},
      {"runs", runs},
  };
}

}  // namespace snee
