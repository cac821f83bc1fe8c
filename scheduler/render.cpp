#include "scheduler/render.h"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <stdexcept>
#include <string>

#include "kernels/physics/lights/light_table.h"
#include "kernels/physics/snee/light_extent.h"
#include "kernels/simd/arch.h"
#include "kernels/stages/first_hit_aovs.h"
#include "scene/embree_scene.h"
#include "scheduler/schedule.h"
#include "scheduler/simd_backend.h"
#include "scheduler/threading.h"
#include "scheduler/unit_schedules.h"
#include "scheduler/work_unit.h"

namespace snee {

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

int max_render_threads() {
  return kMaxThreadsPerHardwareThread * tbb::info::default_concurrency();
}

namespace {

void validate(const Scene& scene, const RenderOptions& o, const RenderHooks& hooks,
              const FilmState* resume) {
  if (o.spp < 1) throw std::invalid_argument("spp must be at least 1");
  if (o.threads < 0 || o.threads > max_render_threads())
    throw std::invalid_argument("threads must be 0 (all) or from 1 to " +
                                std::to_string(max_render_threads()));
  // Depth 0 is allowed, as in the scene format: paths end at their first hit (camera rays and
  // directly visible emission only).
  if (o.max_depth < 0) throw std::invalid_argument("max depth must not be negative");
  if (o.queue_capacity < kMinQueueCapacity || o.queue_capacity > kMaxQueueCapacity)
    throw std::invalid_argument("queue capacity must be from " + std::to_string(kMinQueueCapacity) +
                                " to " + std::to_string(kMaxQueueCapacity));
  if (o.tile_size < 1 || o.tile_size > kMaxTileSize)
    throw std::invalid_argument("tile size must be from 1 to " + std::to_string(kMaxTileSize));
  if (o.samples_per_unit < 1 || o.samples_per_unit > kMaxSamplesPerUnit)
    throw std::invalid_argument("samples per unit must be from 1 to " +
                                std::to_string(kMaxSamplesPerUnit));
  if (o.shard_count < 1 || o.shard < 0 || o.shard >= o.shard_count)
    throw std::invalid_argument("shard must be from 0 to shard count - 1");
  if (scene.camera.width < 1 || scene.camera.height < 1) throw std::invalid_argument("empty image");
  // Written as !(x >= 0) so that NaN is refused too.
  if (!(o.time_seconds >= 0) || !std::isfinite(o.time_seconds))
    throw std::invalid_argument("time budget must be a finite number of seconds, 0 for none");
  if (!(o.noise_target >= 0) || !std::isfinite(o.noise_target))
    throw std::invalid_argument("noise target must be a finite relative error, 0 for none");
  if (hooks.tile_source && (o.time_seconds > 0 || resume || o.shard_count > 1))
    throw std::invalid_argument(
        "tiles claimed while rendering go with no time budget, resumed state or shard");
}

// Units in flight per thread (the window's lead, unit_window.h). A unit holds up the threads
// only once they have run this many units past it, so tiles of very different cost (sky beside
// marble) never idle a thread, while the sample buffers stay a few megabytes per thread.
constexpr size_t kUnitsInFlightPerThread = 32;
// The global schedule keeps this many units per thread in flight.
constexpr size_t kGlobalLanesPerThread = 8;

// A workspace's path state, queues and scratch per slot: 2.4 KiB measured in this build (220
// bytes of it PathState), rounded up so that the queues may grow a little before this is wrong.
constexpr uint64_t kWorkspaceBytesPerSlot = 4096;
// A tile's place in the unit grid and its lock and parked-unit list in the film.
constexpr uint64_t kBytesPerTile = 128;

// The large allocations of a render, computed from its size before any is made: the film's sums
// (double) and the resolved film (mean, variance and sample count), the tiles, one sample
// buffer per unit in the window, and every workspace.
uint64_t render_memory_bytes(const Scene& scene, const RenderOptions& o, int threads,
                             Schedule schedule) {
  const uint64_t width = static_cast<uint64_t>(scene.camera.width);
  const uint64_t height = static_cast<uint64_t>(scene.camera.height);
  const uint64_t tile = static_cast<uint64_t>(o.tile_size);
  const uint64_t pixels = saturating_multiply(width, height);
  // AOVs: kAovFloats sums per pixel, their resolved layers and kAovFloats floats per sample.
  const uint64_t aov_floats = o.aovs.any() ? kAovFloats : 0;
  const uint64_t film =
      saturating_multiply(pixels, (6 + aov_floats) * sizeof(double) + 2 * sizeof(Rgb) +
                                      sizeof(uint32_t) + aov_floats * sizeof(float));
  const uint64_t tiles = ((width + tile - 1) / tile) * ((height + tile - 1) / tile) /
                             static_cast<uint64_t>(o.shard_count) +
                         1;
  const uint64_t chunks = (static_cast<uint64_t>(o.spp) + o.samples_per_unit - 1) /
                          static_cast<uint64_t>(o.samples_per_unit);
  const uint64_t lead = std::min(saturating_multiply(tiles, chunks),
                                 kUnitsInFlightPerThread * static_cast<uint64_t>(threads));
  const uint64_t unit_samples = saturating_multiply(
      std::min(tile, width) * std::min(tile, height),
      std::min(static_cast<uint64_t>(o.spp), static_cast<uint64_t>(o.samples_per_unit)));
  const uint64_t buffers = saturating_multiply(saturating_multiply(lead, unit_samples),
                                               sizeof(Rgb) + aov_floats * sizeof(float));
  const uint64_t workspaces_count =
      threads + (schedule == Schedule::kGlobal ? kGlobalLanesPerThread * threads : 0);
  const uint64_t slots = schedule == Schedule::kMegakernel ? 1 : o.queue_capacity;
  const uint64_t workspaces =
      saturating_multiply(saturating_multiply(workspaces_count, slots), kWorkspaceBytesPerSlot);
  return saturating_add(saturating_add(film, saturating_multiply(tiles, kBytesPerTile)),
                        saturating_add(buffers, workspaces));
}

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

ShortestFreePath shortest_free_path(const Scene& scene, float clearance) {
  ShortestFreePath shortest;
  for (const Medium& m : scene.media) {
    // A grid medium is densest where its grid is (the coefficients are those at density 1).
    const double peak = m.density ? m.density->max_value : 1.0;
    const double densest = peak * std::max({m.sigma_t().x, m.sigma_t().y, m.sigma_t().z});
    const double clearances = 1.0 / (densest * clearance);
    if (densest > 0 && clearances < shortest.clearances) shortest = {clearances, m.name};
  }
  return shortest;
}

namespace {

// render() at this compilation's SIMD level (simd_dispatch.cpp chooses among the levels).
RenderResult render_compiled_level(const Scene& scene, const RenderOptions& options,
                                   const RenderHooks& hooks, const FilmState* resume) {
  validate(scene, options, hooks, resume);
  const Integrator requested = parse_integrator(options.integrator);
  // SNEE pays only for lights that unidirectional sampling rarely finds (docs/method.md 3.11).
  const float smallest_light = smallest_light_half_angle_degrees(scene);
  const bool snee_engaged =
      requested == Integrator::kSnee && smallest_light <= options.snee.light_limit_degrees;
  const Integrator integrator =
      requested == Integrator::kSnee && !snee_engaged ? Integrator::kPathTracer : requested;
  // Bottom-to-top finds a light only by looking up the direction it refracts out along, which
  // reaches a small light as rarely as the tracer's own exit does (docs/method.md 3.11). A limit
  // of 180 keeps every strategy on.
  SneeOptions snee_options = options.snee;
  if (snee_options.light_limit_degrees < kWholeSkyDegrees &&
      largest_escaped_light_half_angle_degrees(scene) <= snee_options.light_limit_degrees)
    snee_options.enabled = snee_options.enabled.without(Strategy::kBottomToTop);
  const Schedule schedule = parse_schedule(options.schedule);
  const auto start = std::chrono::steady_clock::now();
  set_flush_to_zero();
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  const uint64_t memory = render_memory_bytes(scene, options, threads, schedule);
  if (!options.memory_budget.allows(memory)) {
    throw std::invalid_argument(options.memory_budget.exceeded(
        "the film and work buffers of " + std::to_string(scene.camera.width) + "x" +
            std::to_string(scene.camera.height) + " pixels on " + std::to_string(threads) +
            " threads",
        memory));
  }
  tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism,
                                   static_cast<size_t>(threads));
  tbb::task_arena arena(threads);

  const EmbreeScene embree(scene);
  const LightTable lights(scene, options.light_selection);
  KernelContext ctx(scene, embree, lights, integrator, options.seed, options.max_depth,
                    snee_options, options.memory_budget);
  ctx.sample_clamp = options.sample_clamp;
  ctx.record_aovs = options.aovs.any();
  const auto sampling_start = std::chrono::steady_clock::now();
  const double sampling_cpu_start = cpu_seconds();

  const int width = scene.camera.width, height = scene.camera.height;
  const uint32_t spp = static_cast<uint32_t>(options.spp);
  const UnitGrid grid(width, height, options.tile_size, spp,
                      static_cast<uint32_t>(options.samples_per_unit), options.shard,
                      options.shard_count,
                      hooks.tile_source ? UnitOrder::kTileMajor : UnitOrder::kRoundMajor);
  TileClaims claims(grid.tile_count(), hooks.tile_source);
  TileCosts costs(grid.raster_tile_count());
  // A shard may own no tile at all (more processes than tiles); its window still needs a lead.
  const size_t lead = std::max<size_t>(1, std::min(grid.size(), kUnitsInFlightPerThread * threads));
  UnitWindow window(grid.size(), lead);
  FilmAccumulator film_sums(grid, width, height, lead, options.noise_target);
  uint32_t rounds_begun = 0;
  double resumed_seconds = 0;
  if (resume) {
    film_sums.restore(*resume);
    for (const TileState& t : resume->tiles) rounds_begun = std::max(rounds_begun, t.chunks);
    resumed_seconds = resume->seconds;
  }
  if (options.aovs.any()) film_sums.keep_aovs();
  FilmMetadata meta;
  meta.integrator = integrator_name(requested);
  meta.seed = options.seed;
  meta.scene = scene.name;
  meta.time_budget_seconds = options.time_seconds;
  meta.noise_target = options.noise_target;
  UnitProgress unit_progress(hooks, grid.sample_count(), start, film_sums, meta, resumed_seconds);
  const auto resumed_start =
      start - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                  std::chrono::duration<double>(resumed_seconds));
  TimeBudget time_budget(options.time_seconds, resumed_start, rounds_begun);
  const UnitSource source{grid, window, film_sums, unit_progress, time_budget, claims, costs};

  // The megakernel is the same loop over one-slot workspaces: one path at a time per thread.
  const size_t slots =
      schedule == Schedule::kMegakernel ? 1 : static_cast<size_t>(options.queue_capacity);
  const bool snee_memory = ctx.integrator == Integrator::kSnee;
  ThreadWorkspaces workspaces(slots, snee_memory);
  std::vector<std::unique_ptr<UnitWorkspace>> lanes;
  if (schedule == Schedule::kGlobal) {
    const size_t lane_count = std::min(lead, kGlobalLanesPerThread * threads);
    for (size_t i = 0; i < lane_count; ++i)
      lanes.push_back(std::make_unique<UnitWorkspace>(slots, snee_memory));
  }
  arena.execute([&] {
    if (schedule == Schedule::kGlobal) {
      run_units_breadth_first(ctx, source, lanes);
    } else {
      run_units_depth_first(ctx, source, threads, workspaces);
    }
  });

  RenderResult result;
  if (hooks.checkpoint_state) result.state = unit_progress.state();
  result.film = film_sums.resolve(meta);
  Film& film = result.film;
  // All three are recorded together (they end at one vertex); only the chosen ones are kept.
  if (!options.aovs.albedo) film.albedo.clear();
  if (!options.aovs.normal) film.normal.clear();
  if (!options.aovs.depth) film.depth.clear();
  // Complete: every tile holds the rounds it was to take, or has met the noise target.
  result.complete = film_sums.tiles_done(time_budget.rounds(grid.chunk_count()),
                                         [&](size_t t) { return claims.claimed(t); });
  result.time_budget_spent = time_budget.spent();
  RenderStats& stats = result.stats;
  const auto end = std::chrono::steady_clock::now();
  stats.seconds = std::chrono::duration<double>(end - start).count();
  stats.sampling_seconds = std::chrono::duration<double>(end - sampling_start).count();
  stats.sampling_cpu_seconds = cpu_seconds() - sampling_cpu_start;
  stats.threads = threads;
  stats.tiles_rendered = costs.tiles_run();
  stats.tile_seconds = costs.seconds();
  stats.path_state_bytes_per_slot = PathState::bytes_per_slot(snee_memory);
  KernelCounters counters;
  uint64_t slot_turns = 0, active_slot_turns = 0;
  for (const UnitWorkspace& ws : workspaces)
    add_workspace_stats(ws, counters, stats, slot_turns, active_slot_turns);
  for (const auto& lane : lanes)
    add_workspace_stats(*lane, counters, stats, slot_turns, active_slot_turns);
  stats.queue_occupancy =
      slot_turns > 0 ? static_cast<double>(active_slot_turns) / static_cast<double>(slot_turns) : 0;
  stats.rays = counters.rays;
  stats.paths = counters.paths;
  stats.nonfinite_samples = counters.nonfinite_samples;
  stats.snee = counters.snee;
  stats.snee_engaged = snee_engaged;
  stats.snee_strategies = snee_options.enabled;
  stats.smallest_light_degrees = smallest_light;
  stats.shortest_free_path = shortest_free_path(scene, embree.ray_epsilon());
  stats.simd_lanes = counters.lanes;
  stats.simd_level = kCompiledSimdLevel;
  stats.simd_width = simd::kLanes;
  film.meta.render_seconds = stats.seconds;
  film.meta.nonfinite_samples = stats.nonfinite_samples;
  return result;
}

}  // namespace

const SimdBackend& compiled_backend() {
  static const SimdBackend backend{.render = &render_compiled_level};
  return backend;
}

}  // namespace snee
