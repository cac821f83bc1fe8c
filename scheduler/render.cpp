#include "scheduler/render.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>
#include <stdexcept>

#include "kernels/lights/light_table.h"
#include "kernels/simd/arch.h"
#include "scene/embree_scene.h"
#include "scheduler/pass_schedules.h"
#include "scheduler/schedule.h"
#include "scheduler/threading.h"
#include "scheduler/work_unit.h"

namespace snee {

const char* ray_kind_name(RayKind k) {
  static const char* names[] = {"camera", "extension", "shadow", "probe"};
  return names[static_cast<int>(k)];
}

const char* stage_name(Stage s) {
  static const char* names[] = {"generate",      "extend",         "medium_event",
                                "shade_surface", "shade_escaped",  "snee_probe",
                                "subdivision",   "shadow_connect", "retire"};
  return names[static_cast<int>(s)];
}

uint64_t RenderStats::total_rays() const {
  uint64_t total = 0;
  for (const uint64_t r : rays) total += r;
  return total;
}

LaneCount RenderStats::all_simd_lanes() const {
  LaneCount all;
  for (const LaneCount& k : simd_lanes) {
    all.active += k.active;
    all.run += k.run;
  }
  return all;
}

namespace {

void validate(const Scene& scene, const RenderOptions& o) {
  if (o.spp < 1) throw std::invalid_argument("spp must be at least 1");
  if (o.threads < 0) throw std::invalid_argument("threads must be 0 (all) or positive");
  // Depth 0 is allowed, as in the scene format: paths end at their first hit (camera rays and
  // directly visible emission only).
  if (o.max_depth < 0) throw std::invalid_argument("max depth must not be negative");
  if (o.queue_capacity < 16) throw std::invalid_argument("queue capacity must be at least 16");
  if (o.tile_size < 1) throw std::invalid_argument("tile size must be at least 1");
  if (o.samples_per_pass < 1) throw std::invalid_argument("samples per pass must be at least 1");
  if (scene.camera.width < 1 || scene.camera.height < 1) throw std::invalid_argument("empty image");
}

// A pass holds at least this many units (when the image and spp allow). It is a constant, not
// a multiple of the thread count, so every thread count runs the same passes: scaling studies
// then compare equal work with equal barriers.
constexpr size_t kMinUnitsPerPass = 128;
// The global schedule keeps this many units per thread in flight.
constexpr size_t kGlobalLanesPerThread = 8;

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

void add_workspace_stats(const UnitWorkspace& ws, KernelCounters& counters, RenderStats& stats,
                         uint64_t& turns, uint64_t& active_slot_turns) {
  counters.add(ws.counters);
  for (int i = 0; i < kStageCount; ++i) {
    stats.stage_seconds[i] += ws.stage_seconds[i];
    stats.stage_calls[i] += ws.stage_calls[i];
  }
  turns += ws.turns * ws.slots;
  active_slot_turns += ws.active_slot_turns;
}

}  // namespace

RenderResult render(const Scene& scene, const RenderOptions& options,
                    const ProgressCallback& progress) {
  validate(scene, options);
  const Integrator integrator = parse_integrator(options.integrator);
  const Schedule schedule = parse_schedule(options.schedule);
  const auto start = std::chrono::steady_clock::now();
  set_flush_to_zero();
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism,
                                   static_cast<size_t>(threads));
  tbb::task_arena arena(threads);

  const EmbreeScene embree(scene);
  const LightTable lights(scene);
  const KernelContext ctx(scene, embree, lights, integrator, options.seed, options.max_depth,
                          options.snee);
  const auto passes_start = std::chrono::steady_clock::now();
  const double passes_cpu_start = cpu_seconds();

  const int width = scene.camera.width, height = scene.camera.height, ts = options.tile_size;
  std::vector<WorkUnit> tiles;
  for (int y = 0; y < height; y += ts) {
    for (int x = 0; x < width; x += ts)
      tiles.push_back({x, y, std::min(x + ts, width), std::min(y + ts, height), 0, 0});
  }
  // A pass renders a block of sample indices for every pixel; its units are tiles times
  // sample chunks. How the block is cut into units never changes the image: every sample is a
  // pure function of its pixel and index, and the film adds samples in index order.
  const uint32_t spp = static_cast<uint32_t>(options.spp);
  const uint32_t chunk = static_cast<uint32_t>(options.samples_per_pass);
  const uint32_t chunks_per_pass = static_cast<uint32_t>(std::clamp<size_t>(
      (kMinUnitsPerPass + tiles.size() - 1) / tiles.size(), 1, (spp + chunk - 1) / chunk));

  const size_t pixel_count = static_cast<size_t>(width) * height;
  std::vector<double> sum(pixel_count * 3, 0.0), sum_sq(pixel_count * 3, 0.0);
  std::vector<Rgb> pass_samples(pixel_count *
                                std::min<size_t>(spp, size_t{chunk} * chunks_per_pass));

  // The megakernel is the same loop over one-slot workspaces: one path at a time per thread.
  const size_t slots =
      schedule == Schedule::kMegakernel ? 1 : static_cast<size_t>(options.queue_capacity);
  ThreadWorkspaces workspaces(slots);
  std::vector<std::unique_ptr<UnitWorkspace>> lanes;
  if (schedule == Schedule::kGlobal) {
    const size_t lane_count =
        std::min(tiles.size() * chunks_per_pass, kGlobalLanesPerThread * threads);
    for (size_t i = 0; i < lane_count; ++i) lanes.push_back(std::make_unique<UnitWorkspace>(slots));
  }
  UnitProgress unit_progress(progress, static_cast<int64_t>(pixel_count) * spp, start);

  for (uint32_t pass_begin = 0; pass_begin < spp; pass_begin += chunk * chunks_per_pass) {
    const uint32_t pass_end = std::min(spp, pass_begin + chunk * chunks_per_pass);
    Pass pass;
    size_t offset = 0;
    for (uint32_t s = pass_begin; s < pass_end; s += chunk) {
      for (WorkUnit u : tiles) {
        u.sample_begin = s;
        u.sample_end = std::min(pass_end, s + chunk);
        pass.units.push_back(u);
        pass.offsets.push_back(offset);
        offset += u.sample_count();
      }
    }
    arena.execute([&] {
      if (schedule == Schedule::kGlobal) {
        run_pass_breadth_first(ctx, pass, pass_samples.data(), lanes, unit_progress);
      } else {
        run_pass_depth_first(ctx, pass, pass_samples.data(), workspaces, unit_progress);
      }
      // Fold the pass into the film: tiles in parallel, and within a tile its sample chunks in
      // order, so every pixel adds its samples in index order whatever the thread count.
      tbb::parallel_for(size_t{0}, tiles.size(), [&](size_t t) {
        for (size_t i = t; i < pass.units.size(); i += tiles.size()) {
          const WorkUnit& u = pass.units[i];
          const Rgb* samples = pass_samples.data() + pass.offsets[i];
          const int tile_w = u.x1 - u.x0;
          for (uint32_t s = 0; s < u.sample_end - u.sample_begin; ++s) {
            for (int y = u.y0; y < u.y1; ++y) {
              for (int x = u.x0; x < u.x1; ++x) {
                const Rgb v = samples[s * static_cast<size_t>(u.pixel_count()) +
                                      static_cast<size_t>((y - u.y0) * tile_w + (x - u.x0))];
                const size_t pixel = static_cast<size_t>(y) * width + x;
                for (int c = 0; c < 3; ++c) {
                  sum[3 * pixel + c] += v[c];
                  sum_sq[3 * pixel + c] += static_cast<double>(v[c]) * v[c];
                }
              }
            }
          }
        }
      });
    });
  }

  RenderResult result;
  Film& film = result.film;
  film.width = width;
  film.height = height;
  film.mean.resize(pixel_count);
  film.variance_of_mean.resize(pixel_count);
  const double n = spp;
  for (size_t p = 0; p < pixel_count; ++p) {
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[3 * p + c] / n;
      const double var =
          spp > 1 ? std::max(0.0, (sum_sq[3 * p + c] - n * mean * mean) / (n - 1)) : 0.0;
      film.mean[p][c] = static_cast<float>(mean);
      film.variance_of_mean[p][c] = static_cast<float>(var / n);
    }
  }
  RenderStats& stats = result.stats;
  const auto end = std::chrono::steady_clock::now();
  stats.seconds = std::chrono::duration<double>(end - start).count();
  stats.pass_seconds = std::chrono::duration<double>(end - passes_start).count();
  stats.pass_cpu_seconds = cpu_seconds() - passes_cpu_start;
  stats.threads = threads;
  stats.path_state_bytes_per_slot = PathState::bytes_per_slot();
  KernelCounters counters;
  uint64_t slot_turns = 0, active_slot_turns = 0;
  for (const UnitWorkspace& ws : workspaces)
    add_workspace_stats(ws, counters, stats, slot_turns, active_slot_turns);
  for (const auto& lane : lanes)
    add_workspace_stats(*lane, counters, stats, slot_turns, active_slot_turns);
  stats.queue_occupancy =
      slot_turns > 0 ? static_cast<double>(active_slot_turns) / static_cast<double>(slot_turns) : 0;
  for (int i = 0; i < static_cast<int>(RayKind::kCount); ++i) stats.rays[i] = counters.rays[i];
  stats.paths = counters.paths;
  stats.nonfinite_samples = counters.nonfinite_samples;
  stats.snee = counters.snee;
  stats.simd_lanes = counters.lanes;
  stats.simd_width = simd::kLanes;
  film.meta.spp = options.spp;
  film.meta.integrator = integrator_name(integrator);
  film.meta.seed = options.seed;
  film.meta.render_seconds = stats.seconds;
  film.meta.scene = scene.name;
  return result;
}

}  // namespace snee
