// Whole stage kernels over one work unit's queue (256 slots, the default unit), from a fixed
// starting state restored before every iteration (outside the timing): medium_event (SIMD
// flights, then the per-slot pass) and shade_surface (SIMD dielectric samples, then light
// sampling and routing), on the grid's translucent sphere under its cone light, path tracer.
#include <benchmark/benchmark.h>

#include <random>

#include "kernels/physics/lights/light_table.h"
#include "kernels/stages/stages.h"
#include "scene/embree_scene.h"
#include "scene/scene_loader.h"

namespace snee {
namespace {

constexpr size_t kSlots = 256;

struct StageBench {
  StageBench()
      : scene(load_builtin_scene("sphere-cone-r0.04").scene),
        embree(scene),
        lights(scene),
        ctx(scene, embree, lights, Integrator::kPathTracer, 1, 1024, SneeOptions{}),
        start(kSlots, false),
        state(kSlots, false),
        queues(kSlots) {}

  // Paths at their fourth vertex (so roulette runs), with random directions from random
  // points, all in the sphere's medium (inside) or all outside aimed at the sphere.
  void start_paths(bool inside) {
    std::mt19937 engine(3);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t s = 0; s < kSlots; ++s) {
      const Vec3 p = normalize(Vec3(normal(engine), normal(engine), normal(engine)));
      const Vec3 o = inside ? p * (0.9f * unit(engine)) : p * 3.0f;
      const Vec3 target = normalize(Vec3(normal(engine), normal(engine), normal(engine))) * 0.5f;
      const Vec3 d = inside ? normalize(Vec3(normal(engine), normal(engine), normal(engine)))
                            : normalize(target - o);
      start.pixel[s] = s;
      start.sample[s] = 0;
      start.event[s] = 4;
      start.depth[s] = 4;
      start.flags[s] = 0;
      start.medium[s] = inside ? 0 : -1;
      start.set_throughput(s, Rgb(0.5f));
      start.radiance_r[s] = start.radiance_g[s] = start.radiance_b[s] = 0.0f;
      start.mis_pdf[s] = 0.0f;
      start.eta_scale[s] = 1.0f;
      start.set_channel_probabilities(s, Rgb(1.0f / 3.0f));
      start.set_ray(s, o, d);
      start.push_vertex(s, o, d, inside);
      start.push_vertex(s, o, d, inside);
      queues.extend.push(s);
    }
    // The real first hits.
    KernelCounters counters;
    extend(ctx, start, queues, counters);
    clear_queues();
  }
  void clear_queues() {
    for (SlotQueue* queue : {&queues.extend, &queues.medium, &queues.surface, &queues.escaped,
                             &queues.probe, &queues.retire})
      queue->clear();
    queues.shadow.clear();
  }

  Scene scene;
  EmbreeScene embree;
  LightTable lights;
  KernelContext ctx;
  PathState start, state;
  StageQueues queues;
};

template <typename Stage>
void run_stage(benchmark::State& bench_state, bool inside, SlotQueue StageQueues::*input,
               Stage stage) {
  StageBench b;
  b.start_paths(inside);
  KernelCounters counters;
  for (auto _ : bench_state) {
    bench_state.PauseTiming();
    b.state.copy_from(b.start);
    b.clear_queues();
    for (uint32_t s = 0; s < kSlots; ++s) (b.queues.*input).push(s);
    bench_state.ResumeTiming();
    stage(b.ctx, b.state, b.queues, counters);
    benchmark::ClobberMemory();
  }
  bench_state.SetItemsProcessed(bench_state.iterations() * static_cast<int64_t>(kSlots));
}

void BM_MediumEventStage(benchmark::State& state) {
  run_stage(state, true, &StageQueues::medium, medium_event);
}
BENCHMARK(BM_MediumEventStage);

void BM_ShadeSurfaceStage(benchmark::State& state) {
  run_stage(state, false, &StageQueues::surface, shade_surface);
}
BENCHMARK(BM_ShadeSurfaceStage);

}  // namespace
}  // namespace snee
