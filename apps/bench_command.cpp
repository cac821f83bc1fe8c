#include "apps/bench_command.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "apps/bench_report.h"
#include "apps/bench_workloads.h"
#include "apps/option_checks.h"
#include "apps/resolution.h"
#include "apps/simd_option.h"
#include "apps/stats_json.h"
#include "apps/thread_counts.h"
#include "kernels/wavefront/path_state.h"
#include "scene/embree_scene.h"
#include "scheduler/simd_dispatch.h"
#include "scheduler/threading.h"

namespace snee {

namespace {

constexpr const char* kSchedules[] = {"megakernel", "local", "global"};

struct Settings {
  std::vector<int> threads;
  int spp, repeats;
  Resolution resolution;
  size_t raw_rays;
  int raw_repeats;
};

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.starts_with("model name")) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::localtime(&now));
  return buf;
}

size_t triangle_count(const Scene& scene) {
  size_t n = 0;
  for (const Shape& s : scene.shapes) n += s.mesh.triangle_count();
  return n;
}

// Peak memory at spp and 4 spp on the same workload: the film and the units' sample buffers are
// the only allocations that could grow with spp, and the unit window bounds the buffers.
nlohmann::ordered_json memory_versus_spp(const BenchWorkload& w, const Settings& settings) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const int spp : {settings.spp, 4 * settings.spp}) {
    RenderOptions o;
    o.spp = spp;
    o.integrator = w.integrator;
    o.max_depth = w.max_depth;
    o.threads = settings.threads.back();
    const Measurement m = measure_render(w.scene, o, 1);
    runs.push_back({{"spp", spp}, {"peak_memory_mib", m.peak_memory_mib()}});
  }
  return {{"workload", w.name},
          {"schedule", "local"},
          {"threads", settings.threads.back()},
          {"runs", runs}};
}

}  // namespace

BenchCommand::BenchCommand(CLI::App& parent)
    : command_(parent.add_subcommand(
          "bench", "Measure throughput of every schedule on fixed workloads, against raw Embree")) {
  CLI::App& c = *command_;
  dragon_ = default_dragon_path();
  c.add_option("--threads", threads_, "Comma-separated thread counts, e.g. 1,2")
      ->check(thread_counts_validator())
      ->capture_default_str();
  c.add_option("--spp", spp_, "Samples per pixel (the camera workload takes 16x as many)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c.add_option("--resolution", resolution_, "Image size WxH of every workload")
      ->check(resolution_validator())
      ->capture_default_str();
  c.add_option("--repeats", repeats_, "Renders per measurement; the median is reported")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c.add_option("--samples-per-unit", samples_per_unit_,
               "Sample indices per pixel in one work unit (a tile times this many samples)")
      ->check(integer_in_range(1, kMaxSamplesPerUnit))
      ->capture_default_str();
  c.add_option("--queue-capacity", queue_capacity_,
               "Path slots per work unit of the local and global schedules")
      ->check(integer_in_range(kMinQueueCapacity, kMaxQueueCapacity))
      ->capture_default_str();
  c.add_flag("--quick", quick_,
             "Tiny smoke run (16x16, 1 spp, 1 repeat, no dragon) unless options say otherwise");
  c.add_option("--json", json_, "Also write the results as JSON to this file");
  c.add_option("--dragon", dragon_, "The Stanford dragon mesh (dragon_vrip.ply)")
      ->capture_default_str();
  c.add_option("--only", only_, "Comma-separated workload names to run (default: all)");
  c.add_option("--simd", simd_,
               "Comma-separated SIMD levels (sse4.2, avx2, avx512) or all: every run is measured "
               "at each, and xsimd is its paths per CPU-second over the first's [default: the "
               "widest this machine runs]");
}

int BenchCommand::run() const {
  Settings settings;
  settings.threads = capped_thread_counts(*parse_thread_counts(threads_));
  settings.spp = quick_ && !given("--spp") ? 1 : spp_;
  settings.repeats = quick_ && !given("--repeats") ? 1 : repeats_;
  settings.resolution = *parse_resolution(quick_ && !given("--resolution") ? "16x16" : resolution_);
  settings.raw_rays = quick_ ? size_t{1} << 12 : size_t{1} << 18;
  settings.raw_repeats = quick_ ? 1 : 3;
  // Without --simd each schedule runs at its default level (simd_dispatch.h).
  const std::vector<SimdLevel> levels =
      simd_.empty() ? std::vector<SimdLevel>{} : parse_simd_levels(simd_);
  std::vector<SimdLevel> measured = levels;
  if (levels.empty()) {
    for (const char* schedule : kSchedules) {
      const SimdLevel level = default_simd_level(schedule);
      if (std::find(measured.begin(), measured.end(), level) == measured.end())
        measured.push_back(level);
    }
  }
  set_flush_to_zero();

  BenchWorkloads set = bench_workloads(dragon_, !quick_);
  if (!only_.empty()) {
    const std::string list = "," + only_ + ",";
    std::erase_if(set.workloads, [&](const BenchWorkload& w) {
      return list.find("," + w.name + ",") == std::string::npos;
    });
    if (set.workloads.empty()) throw std::invalid_argument("--only names no workload: " + only_);
  }
  for (const std::string& message : set.skipped) std::fprintf(stderr, "%s\n", message.c_str());
  std::printf("snee bench %s: %s, %u hardware threads; %dx%d, %d spp, %d repeat(s), threads",
              today().c_str(), cpu_model().c_str(), std::thread::hardware_concurrency(),
              settings.resolution.width, settings.resolution.height, settings.spp,
              settings.repeats);
  for (const int t : settings.threads) std::printf(" %d", t);
  std::printf("\npath state: %zu bytes per slot (%zu for snee, with its vertex memory); SIMD",
              PathState::bytes_per_slot(false), PathState::bytes_per_slot(true));
  for (const SimdLevel level : levels) std::printf(" %s", simd_level_description(level).c_str());
  std::printf(" (\"lanes\": occupancy of the batched kernels' lanes)\n");

  nlohmann::ordered_json workloads = nlohmann::ordered_json::array();
  for (BenchWorkload& w : set.workloads) {
    w.scene.camera.width = settings.resolution.width;
    w.scene.camera.height = settings.resolution.height;
    BenchResult result;
    result.workload = &w;
    result.spp = settings.spp * w.spp_factor;
    result.triangles = triangle_count(w.scene);
    result.simd_levels = levels;
    {
      const EmbreeScene embree(w.scene);
      result.raw =
          measure_embree_throughput(w.scene, embree, settings.raw_rays, settings.raw_repeats);
    }
    for (const int threads : settings.threads) {
      // The runs' repeats are interleaved, so other work on a shared machine slows the
      // compared schedules and SIMD levels alike.
      std::vector<BenchRun> runs;
      if (levels.empty()) {
        for (const char* schedule : kSchedules)
          runs.push_back({schedule, threads, 0, default_simd_level(schedule), Measurement()});
      }
      for (const SimdLevel level : levels)
        for (const char* schedule : kSchedules)
          runs.push_back({schedule, threads, 0, level, Measurement()});
      for (int r = 0; r < settings.repeats; ++r) {
        for (BenchRun& run : runs) {
          RenderOptions o;
          o.spp = result.spp;
          o.threads = threads;
          o.integrator = w.integrator;
          o.max_depth = w.max_depth;
          o.schedule = run.schedule;
          o.samples_per_unit = samples_per_unit_;
          o.queue_capacity = queue_capacity_;
          o.simd = run.simd;
          run.queue_capacity = run.schedule == "megakernel" ? 1 : o.queue_capacity;
          run.measurement.repeat(w.scene, o);
        }
      }
      for (BenchRun& run : runs) result.runs.push_back(std::move(run));
    }
    print_bench_result(stdout, result);
    std::fflush(stdout);
    workloads.push_back(bench_result_json(result));
  }

  // The memory check runs on the bunny path tracer, or the first workload if that was left out.
  const auto bunny = std::find_if(set.workloads.begin(), set.workloads.end(),
                                  [](const BenchWorkload& w) { return w.name == "bunny-pt"; });
  const BenchWorkload& probe = bunny != set.workloads.end() ? *bunny : set.workloads.front();
  nlohmann::ordered_json memory = memory_versus_spp(probe, settings);
  std::printf("\npeak memory vs spp (%s, local, %d threads):", probe.name.c_str(),
              settings.threads.back());
  for (const auto& run : memory["runs"])
    std::printf(" %d spp %.1f MiB", run["spp"].get<int>(), run["peak_memory_mib"].get<double>());
  std::printf("\n");

  if (!json_.empty()) {
    const nlohmann::ordered_json json = {
        {"version", SNEE_VERSION},
        {"date", today()},
        {"machine",
         {{"cpu", cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()}}},
        {"settings",
         {{"threads", settings.threads},
          {"spp", settings.spp},
          {"resolution",
           {{"width", settings.resolution.width}, {"height", settings.resolution.height}}},
          {"repeats", settings.repeats},
          {"samples_per_unit", samples_per_unit_},
          {"queue_capacity", queue_capacity_},
          {"quick", quick_},
          {"raw_rays_per_query", settings.raw_rays},
          {"raw_repeats", settings.raw_repeats},
          {"schedules", kSchedules}}},
        {"path_state_bytes_per_slot", PathState::bytes_per_slot(false)},
        {"path_state_bytes_per_slot_snee", PathState::bytes_per_slot(true)},
        {"simd_levels",
         [&] {
           nlohmann::ordered_json names = nlohmann::ordered_json::array();
           for (const SimdLevel level : measured) names.push_back(simd_level_name(level));
           return names;
         }()},
        {"skipped", set.skipped},
        {"workloads", workloads},
        {"memory_vs_spp", memory},
    };
    write_json_file(json, json_);
    std::printf("wrote %s\n", json_.c_str());
  }
  return 0;
}

}  // namespace snee
