// Camera-path generation for one queue of slots: the scalar loop the renderer used before
// (random_block + camera_ray per slot) against the batched generate_camera_rays. Argument
// 0: slots 0, 1, 2, ... as a fresh work unit hands them out (vector stores); 1: shuffled slots,
// as they come back from retired paths (scatter stores).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "benchmarks/bench_inputs.h"
#include "kernels/physics/camera.h"
#include "kernels/physics/rng.h"
#include "kernels/stages/stages.h"

namespace snee {
namespace {

struct CameraFixture {
  explicit CameraFixture(bool shuffled)
      : scene(tiny_scene()),
        embree(scene),
        lights(scene),
        ctx(scene, embree, lights, Integrator::kPathTracer, 1, 16, SneeOptions{}),
        state(bench::kItems, false),
        queues(bench::kItems),
        slots(bench::kItems),
        pixels(bench::kItems),
        samples(bench::kItems, 3) {
    std::iota(slots.begin(), slots.end(), 0u);
    std::iota(pixels.begin(), pixels.end(), 0u);
    if (shuffled) std::shuffle(slots.begin(), slots.end(), std::mt19937(1));
  }
  static Scene tiny_scene() {
    Scene s;
    s.camera.width = s.camera.height = 64;  // one sample for each of kItems pixels
    return s;
  }
  Scene scene;
  EmbreeScene embree;
  LightTable lights;
  KernelContext ctx;
  PathState state;
  StageQueues queues;
  KernelCounters counters;
  std::vector<uint32_t> slots, pixels, samples;
};

void generate_scalar(CameraFixture& f) {
  const FilmCamera camera = film_camera(f.ctx.camera, f.ctx.width, f.ctx.height);
  PathState& st = f.state;
  for (size_t i = 0; i < bench::kItems; ++i) {
    const uint32_t s = f.slots[i];
    st.pixel[s] = f.pixels[i];
    st.sample[s] = f.samples[i];
    st.event[s] = st.depth[s] = st.flags[s] = 0;
    st.medium[s] = -1;
    st.set_throughput(s, Rgb(1.0f));
    st.radiance_r[s] = st.radiance_g[s] = st.radiance_b[s] = 0.0f;
    st.mis_pdf[s] = 0.0f;
    st.eta_scale[s] = 1.0f;
    const RandomBlock r =
        random_block(f.ctx.seed, f.pixels[i], f.samples[i], 0, RngPurpose::kCamera);
    const CameraRayOf<float> ray = camera_ray(camera, f.pixels[i], r);
    st.set_ray(s, ray.origin, ray.direction);
    f.queues.extend.push(s);
  }
}

void BM_CameraRaysScalar(benchmark::State& state) {
  CameraFixture f(state.range(0) != 0);
  for (auto _ : state) {
    f.queues.extend.clear();
    generate_scalar(f);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_CameraRaysScalar)->Arg(0)->Arg(1);

void BM_CameraRaysSimd(benchmark::State& state) {
  CameraFixture f(state.range(0) != 0);
  for (auto _ : state) {
    f.queues.extend.clear();
    generate_camera_rays(f.ctx, f.state, f.slots.data(), f.pixels.data(), f.samples.data(),
                         bench::kItems, f.queues, f.counters);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench::kItems));
}
BENCHMARK(BM_CameraRaysSimd)->Arg(0)->Arg(1);

}  // namespace
}  // namespace snee
