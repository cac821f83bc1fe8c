// The entry point of rendering: runs an integrator over a scene with a schedule, a thread
// count and a sample budget, and returns the film and the statistics.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "kernels/physics/snee/snee_options.h"
#include "kernels/simd/simd_level.h"
#include "kernels/stages/stage_table.h"
#include "kernels/wavefront/kernel_context.h"
#include "kernels/wavefront/snee_counters.h"
#include "scene/aov_selection.h"
#include "scene/film.h"
#include "scene/memory_budget.h"
#include "scene/scene.h"
#include "scheduler/film_state.h"

namespace snee {

// Limits render() enforces; the command line checks the same constants.
inline constexpr int kMinQueueCapacity = 16;  // below it a SIMD batch is mostly empty lanes
// 65536 slots of path state are ~12 MiB per thread, far more than a unit's paths need.
inline constexpr int kMaxQueueCapacity = 1 << 16;
// A tile is at most the largest image (kMaxImageEdge, scene/scene.h): a larger one is the same
// single tile, and within the bound a tile's x + tile_size never leaves int.
inline constexpr int kMaxTileSize = kMaxImageEdge;
// Sample indices per pixel in one unit. A unit is the grain of scheduling, of the sample buffer
// and of checkpoints; within this bound sample_begin + samples_per_unit stays below 2^32 for
// any spp (at most 2^31 - 1) in the 32 bits a unit keeps per sample index, and a unit of the
// largest tile holds at most 2^30 x 2^16 samples, which the memory budget then judges.
inline constexpr int kMaxSamplesPerUnit = 1 << 16;
// More threads than hardware threads only add switching to a CPU-bound render, while every
// thread costs a workspace and a share of the sample buffers (~1 MiB), and each must be
// scheduled once to notice a stop; this many per hardware thread leaves room for
// oversubscription experiments without letting a typo start tens of thousands.
inline constexpr int kMaxThreadsPerHardwareThread = 4;
// kMaxThreadsPerHardwareThread x the hardware threads this process may use.
int max_render_threads();

struct RenderOptions {
  int spp = 64;
  uint32_t seed = 0;
  int threads = 0;  // 0 = all hardware threads; at most max_render_threads()
  std::string integrator = "pt";
  int max_depth = 1024;
  int queue_capacity = 256;  // path slots per work unit (batch size of every stage)
  int tile_size = 16;        // work-unit tile edge in pixels (fixed by image, never by threads)
  int samples_per_unit = 8;  // sample indices per pixel in one work unit
  std::string schedule = "local";  // "megakernel", "local" or "global" (scheduler/schedule.h)
  // One process's share of a render split across processes (apps/mpi/): only the tiles whose
  // raster index is `shard` modulo `shard_count` are rendered, the other pixels stay black.
  int shard = 0;
  int shard_count = 1;
  // Budgets (docs/budgets.md), 0 = none. After `time_seconds` of sampling no new round (a chunk
  // of samples_per_unit sample indices over every tile) starts; the rounds started finish.
  // With `noise_target`, each tile takes chunks until its pixels' relative standard error is
  // at most the target (scheduler/noise_target.h) or it holds spp samples.
  double time_seconds = 0;
  double noise_target = 0;
  SneeOptions snee;  // open choices of docs/method.md section 7 (integrator "snee")
  LightSelection light_selection = LightSelection::kUniform;  // docs/lights.md
  // Clip each sample's RGB radiance to this before it is averaged (0: off). Biased: the image
  // no longer converges to the true one; `snee render --clamp`.
  float sample_clamp = 0.0f;
  // Denoiser AOV layers of the film (`snee render --aov`); recording them leaves the beauty
  // image bitwise unchanged.
  AovSelection aovs;
  // The film, sample buffers and workspaces together must fit, or render() refuses before
  // allocating any of them.
  MemoryBudget memory_budget;
  // The SIMD level whose kernels render (scheduler/simd_dispatch.h); unset: the widest this
  // machine can use, or for the megakernel the narrowest. The image is the same at every level.
  std::optional<SimdLevel> simd;
};

struct Progress {
  double fraction = 0;       // 0..1
  int64_t samples_done = 0;  // pixel samples finished
  int64_t samples_total = 0;
  double elapsed_seconds = 0;
  double mrays_per_second = 0;
};
using ProgressCallback = std::function<void(const Progress&)>;

// Tiles [begin, end) by their index in raster order over the whole image (unit_grid.h).
struct TileRange {
  size_t begin = 0;
  size_t end = 0;
};

// What a caller can watch and steer while a render runs; every member is optional. The
// callbacks run on whichever worker just finished a work unit, one checkpoint at a time.
struct RenderHooks {
  ProgressCallback progress;  // after every finished unit
  // The film so far (FilmAccumulator::resolve: each pixel over its own samples, meta.min_spp
  // the fewest), every `checkpoint_seconds` of wall clock; the other workers keep rendering.
  std::function<void(const Film&)> checkpoint;
  // The film's exact state (film_state.h) at the same moments as `checkpoint`: what a later
  // render resumes from. Setting it also fills RenderResult::state.
  std::function<void(const FilmState&)> checkpoint_state;
  double checkpoint_seconds = 0;
  // Asked after every finished unit and between turns of every unit's stage loop, so keep it
  // cheap (an atomic load). Once it says true, no unit starts, the units in flight are
  // dropped at their next turn (their samples never reach the film), and render() returns the
  // film of the units finished so far: a stop takes effect within a turn, whatever the
  // thread count or the cost of a unit.
  std::function<bool()> stop_requested;
  // For processes that share out the tiles while they render (apps/mpi/): each call claims the
  // next tiles in raster order for this process, tiles no other process gets, and returns an
  // empty range once none are left. It is called, one call at a time, whenever the render
  // reaches a tile past its claims; the tiles between two claims are other processes' and stay
  // black here. The units then go tile by tile (UnitOrder::kTileMajor), so a process claims
  // until the very end and a fast one simply claims more. Unset: every tile of the shard is
  // this process's. Not with a time budget (its rounds would be cut at a different tile in
  // every process), a resumed state (that holds a fixed set of tiles) or a shard.
  std::function<TileRange()> tile_source;
};

// One process's part in a render split across processes (RenderStats::processes).
struct ProcessShare {
  int threads = 0;
  uint64_t tiles = 0;       // tiles it ran at least one unit of
  double busy_seconds = 0;  // its sampling wall clock (RenderStats::sampling_seconds)
  double join_seconds = 0;  // waiting for the others at the join, once done
};

// Mean free paths shorter than this many ray clearances are reported (RenderStats): measured on
// a unit sphere of albedo 0.99, 10 clearances render 2% too dark and 1 clearance 25%, while 100
// and more agree with a thin medium within the noise (docs/reliability.md).
inline constexpr double kFreePathClearancesForAccuracy = 100.0;

// The shortest mean free path of a scene's media (1 / the largest sigma_t of any channel), in
// units of the scene's ray clearance (ray_clearance, scene/shape_bounds.h; render() passes the
// one its EmbreeScene already has), and the medium's name; infinite without media. Known before
// rendering, so a front end can warn before a long render.
struct ShortestFreePath {
  double clearances = std::numeric_limits<double>::infinity();
  std::string medium;
};
ShortestFreePath shortest_free_path(const Scene& scene, float clearance);

struct RenderStats {
  double seconds = 0;
  std::array<uint64_t, kRayKinds> rays{};           // by RayKind
  std::array<double, kStageCount> stage_seconds{};  // by Stage, summed over threads
  std::array<uint64_t, kStageCount> stage_calls{};  // by Stage: stage runs on a unit
  double sampling_seconds = 0;      // wall clock of running the work units (no scene setup)
  double sampling_cpu_seconds = 0;  // process CPU time over the same interval, all threads
  double queue_occupancy = 0;       // mean over loop turns of the fraction of slots holding a path
  uint64_t paths = 0;
  uint64_t nonfinite_samples = 0;  // dropped (counted, never averaged in)
  // shortest_free_path of the scene: below kFreePathClearancesForAccuracy, walks near a
  // boundary are distorted by the clearance and a dense object renders too dark
  // (docs/reliability.md, "Numbers").
  ShortestFreePath shortest_free_path;
  SneeCounters snee{};
  // Integrator "snee": whether SNEE ran, i.e. some light looked no larger than
  // SneeOptions::light_limit_degrees (the smallest light's half-angle); otherwise the render
  // was the path tracer's.
  bool snee_engaged = false;
  float smallest_light_degrees = 180.0f;
  // The strategies that ran: SneeOptions::enabled without bottom-to-top when no escaped light is
  // wider than the limit.
  StrategySet snee_strategies;
  std::array<LaneCount, kBatchedKernels> simd_lanes{};  // by BatchedKernel
  SimdLevel simd_level = SimdLevel::kSse42;             // whose kernels rendered
  size_t simd_width = 0;                                // lanes per SIMD batch at that level
  size_t path_state_bytes_per_slot = 0;
  int threads = 0;
  uint64_t tiles_rendered = 0;  // tiles at least one unit of which ran in this render
  // Seconds of the stages of each tile's units, summed over threads, by tile in raster order
  // over the whole image (0 for tiles not run here): the measured cost map of the image.
  std::vector<double> tile_seconds;
  // Of a render split across processes, one per process in rank order, filled in by whoever
  // joins them; empty for one process.
  std::vector<ProcessShare> processes;
  uint64_t total_rays() const;
  LaneCount all_simd_lanes() const;
  double mrays_per_second() const { return seconds > 0 ? total_rays() / seconds * 1e-6 : 0; }
};

struct RenderResult {
  Film film;
  RenderStats stats;
  bool complete = true;  // false when stop_requested cut the render short
  // The time budget stopped the render before spp: every tile that had not met the noise
  // target holds the same whole rounds (film.meta.min_spp samples).
  bool time_budget_spent = false;
  // The film's exact state once the units are done, when RenderHooks::checkpoint_state is set.
  std::optional<FilmState> state;
};

// Runs the kernels of options.simd (scheduler/simd_dispatch.cpp). Throws std::invalid_argument
// for an unknown integrator, a SIMD level this machine cannot use, or invalid options, and when the
// render would need more memory than options.memory_budget. What a hook throws aborts the render
// and propagates, so a caller that wants to go on catches it there. With `resume` (a state that a
// render of the same scene and image-shaping options left, RenderHooks::checkpoint_state) the
// render goes on from it: the units its tiles hold are skipped, and the film ends bitwise the
// one the uninterrupted render makes. Its spp may be larger than the state's render's, when
// that one's chunks were all whole; checking that the state belongs to this render is the
// caller's (the app's checkpoint file records what made it), only its shape is checked here.
RenderResult render(const Scene& scene, const RenderOptions& options, const RenderHooks& hooks = {},
                    const FilmState* resume = nullptr);

}  // namespace snee
