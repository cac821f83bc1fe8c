// Raw Embree traversal throughput on a scene's own geometry: the limit the renderer's rays per
// second are compared with (`snee bench`). Each query kind is timed on a fixed, seeded ray set
// that resembles the renderer's rays of that kind, once as a loop of single-ray calls and once
// as streams. Single-threaded; rates are per CPU-second of the calling thread and per second of
// wall clock.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "scene/embree_scene.h"
#include "scene/scene.h"

namespace snee {

enum class RawQuery : int {
  kCameraSingle,     // primary rays through the pixels in tile order, rtcIntersect1
  kCameraStream,     // the same with rtcIntersect1M, COHERENT, 256 per call
  kClosestSingle,    // from points inside the media-filled shapes, isotropic, tfar = inf
  kClosestStream,    // the same with rtcIntersect1M, INCOHERENT, 256 per call
  kOcclusionSingle,  // segments between two such interior points, rtcOccluded1
  kOcclusionStream,  // the same with rtcOccluded1M, 256 per call
  kCount
};
const char* raw_query_name(RawQuery q);

struct RawRate {
  double mrays_per_second = 0;
  double mrays_per_cpu_second = 0;
};

struct EmbreeThroughput {
  size_t rays_per_query = 0;
  std::array<RawRate, static_cast<int>(RawQuery::kCount)> rate{};  // median of the repeats
  const RawRate& operator[](RawQuery q) const { return rate[static_cast<int>(q)]; }
};

// Interior points are found by tracing from sampled surface points of the shapes that bound a
// medium (every shape if none does), so `embree` must be built from `scene`.
EmbreeThroughput measure_embree_throughput(const Scene& scene, const EmbreeScene& embree,
                                           size_t rays, int repeats);

}  // namespace snee
