#include "benchmarks/embree_throughput.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "scene/camera_frame.h"

namespace snee {

namespace {

// Streams of this many rays: the renderer's batches saturate Embree's streams at 256-1024
// (docs/dependencies.md).
constexpr size_t kStreamSize = 256;
constexpr int kTile = 16;

using Random = std::mt19937_64;

float uniform(Random& rng) {
  return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
}

Vec3 uniform_sphere(Random& rng) {
  const float z = 1.0f - 2.0f * uniform(rng);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * uniform(rng);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

RTCRay make_ray(Vec3 o, Vec3 d, float tfar) {
  return {o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 0.0f, tfar, 0xFFFFFFFFu, 0, 0};
}

RTCRayHit make_ray_hit(Vec3 o, Vec3 d) {
  RTCRayHit rh{};
  rh.ray = make_ray(o, d, kInfinity);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// Pinhole primary rays (the lens's spread does not matter to Embree's speed) through the
// renderer's camera frame, pixel by pixel in work-unit tile
// order; later rounds over the image are jittered within the pixel.
std::vector<RTCRayHit> camera_rays(const Camera& c, size_t n, Random& rng) {
  const CameraFrame f = camera_frame(c);
  std::vector<RTCRayHit> rays;
  rays.reserve(n);
  for (bool first = true; rays.size() < n; first = false) {
    for (int ty = 0; ty < c.height && rays.size() < n; ty += kTile) {
      for (int tx = 0; tx < c.width && rays.size() < n; tx += kTile) {
        for (int y = ty; y < std::min(ty + kTile, c.height) && rays.size() < n; ++y) {
          for (int x = tx; x < std::min(tx + kTile, c.width) && rays.size() < n; ++x) {
            const float jx = first ? 0.5f : uniform(rng), jy = first ? 0.5f : uniform(rng);
            const float sx = 2.0f * (static_cast<float>(x) + jx) / static_cast<float>(c.width) - 1;
            const float sy = 1 - 2.0f * (static_cast<float>(y) + jy) / static_cast<float>(c.height);
            const Vec3 d = normalize(f.forward + f.right * sx + f.up * sy);
            rays.push_back(make_ray_hit(c.position, d));
          }
        }
      }
    }
  }
  return rays;
}

// Area-weighted points on the shapes that bound a medium (all shapes if none does), with their
// outward normals.
class SurfaceSampler {
 public:
  explicit SurfaceSampler(const Scene& scene) : scene_(scene) {
    bool any_medium = false;
    for (const Shape& s : scene.shapes) any_medium = any_medium || s.interior_medium >= 0;
    double total = 0;
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
      const Shape& s = scene.shapes[i];
      if (any_medium && s.interior_medium < 0) continue;
      if (s.kind == ShapeKind::kSphere) {
        total += 4.0 * kPi * s.radius * s.radius;
        push(i, 0, total);
        continue;
      }
      for (size_t t = 0; t < s.mesh.triangle_count(); ++t) {
        const auto [p0, p1, p2] = triangle(s.mesh, t);
        total += 0.5 * length(cross(p1 - p0, p2 - p0));
        push(i, t, total);
      }
    }
  }
  bool empty() const { return cdf_.empty() || !(cdf_.back() > 0); }

  void sample(Random& rng, Vec3* p, Vec3* n) const {
    const double u = uniform(rng) * cdf_.back();
    const size_t k =
        static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    const size_t i = std::min(k, cdf_.size() - 1);
    const Shape& s = scene_.shapes[shape_[i]];
    if (s.kind == ShapeKind::kSphere) {
      *n = uniform_sphere(rng);
      *p = s.center + *n * s.radius;
      return;
    }
    const auto [p0, p1, p2] = triangle(s.mesh, prim_[i]);
    const float r = std::sqrt(uniform(rng)), v = uniform(rng);
    *p = p0 * (1 - r) + p1 * (r * (1 - v)) + p2 * (r * v);
    *n = normalize(cross(p1 - p0, p2 - p0));
  }

 private:
  static std::array<Vec3, 3> triangle(const TriangleMesh& m, size_t t) {
    return {m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
            m.positions[m.indices[3 * t + 2]]};
  }
  void push(size_t shape, size_t prim, double cdf) {
    shape_.push_back(shape);
    prim_.push_back(prim);
    cdf_.push_back(cdf);
  }
  const Scene& scene_;
  std::vector<size_t> shape_, prim_;
  std::vector<double> cdf_;
};

// Points inside the sampled shapes, uniform along chords: a surface point is stepped inward,
// traced across to the far wall, and a random fraction of that chord is kept, like the
// scattering vertices of a random walk.
std::vector<Vec3> interior_points(const Scene& scene, RTCScene rtc, float epsilon, size_t n,
                                  Random& rng) {
  const SurfaceSampler surface(scene);
  std::vector<Vec3> points;
  if (surface.empty()) return points;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  points.reserve(n);
  for (size_t attempts = 0; points.size() < n && attempts < 16 * n; ++attempts) {
    Vec3 p, normal;
    surface.sample(rng, &p, &normal);
    Vec3 d = uniform_sphere(rng);
    if (dot(d, normal) > 0) d = -d;
    const Vec3 o = p - normal * epsilon;
    RTCRayHit rh = make_ray_hit(o, d);
    rtcIntersect1(rtc, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    points.push_back(o + d * (uniform(rng) * rh.ray.tfar));
  }
  return points;
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Times `trace` (which traces a fresh copy of the ray set) `repeats` times; median rates.
template <typename Trace>
RawRate time_query(size_t rays, int repeats, Trace&& trace) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_seconds();
    trace();
    const double cpu_s = thread_cpu_seconds() - cpu_start;
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    wall.push_back(static_cast<double>(rays) / wall_s * 1e-6);
    cpu.push_back(static_cast<double>(rays) / cpu_s * 1e-6);
  }
  auto median = [](std::vector<double>& v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  return {median(wall), median(cpu)};
}

RawRate time_intersect(RTCScene scene, const std::vector<RTCRayHit>& rays, bool stream,
                       bool coherent, int repeats) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags =
      coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  std::vector<RTCRayHit> work(rays.size());
  return time_query(rays.size(), repeats, [&] {
    // The copy restores tfar and the hit records; it is small next to the traversal.
    std::memcpy(work.data(), rays.data(), rays.size() * sizeof(RTCRayHit));
    if (stream) {
      for (size_t i = 0; i < work.size(); i += kStreamSize) {
        const size_t count = std::min(kStreamSize, work.size() - i);
        rtcIntersect1M(scene, &context, work.data() + i, static_cast<unsigned>(count),
                       sizeof(RTCRayHit));
      }
    } else {
      for (RTCRayHit& rh : work) rtcIntersect1(scene, &context, &rh);
    }
  });
}

RawRate time_occluded(RTCScene scene, const std::vector<RTCRay>& rays, bool stream, int repeats) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  std::vector<RTCRay> work(rays.size());
  return time_query(rays.size(), repeats, [&] {
    std::memcpy(work.data(), rays.data(), rays.size() * sizeof(RTCRay));
    if (stream) {
      for (size_t i = 0; i < work.size(); i += kStreamSize) {
        const size_t count = std::min(kStreamSize, work.size() - i);
        rtcOccluded1M(scene, &context, work.data() + i, static_cast<unsigned>(count),
                      sizeof(RTCRay));
      }
    } else {
      for (RTCRay& r : work) rtcOccluded1(scene, &context, &r);
    }
  });
}

}  // namespace

const char* raw_query_name(RawQuery q) {
  static const char* names[] = {"camera_single",  "camera_stream",    "closest_single",
                                "closest_stream", "occlusion_single", "occlusion_stream"};
  return names[static_cast<int>(q)];
}

EmbreeThroughput measure_embree_throughput(const Scene& scene, const EmbreeScene& embree,
                                           size_t rays, int repeats) {
  Random rng(20261201);
  const std::vector<RTCRayHit> camera = camera_rays(scene.camera, rays, rng);
  // One more point than rays, so segment i runs from point i to point i + 1.
  const std::vector<Vec3> points =
      interior_points(scene, embree.scene_, embree.ray_epsilon(), rays + 1, rng);
  std::vector<RTCRayHit> closest;
  std::vector<RTCRay> occlusion;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    closest.push_back(make_ray_hit(points[i], uniform_sphere(rng)));
    const Vec3 to = points[i + 1] - points[i];
    const float distance = length(to);
    if (distance > 0) occlusion.push_back(make_ray(points[i], to / distance, distance * 0.9999f));
  }

  EmbreeThroughput result;
  result.rays_per_query = rays;
  auto set = [&](RawQuery q, RawRate r) { result.rate[static_cast<int>(q)] = r; };
  set(RawQuery::kCameraSingle, time_intersect(embree.scene_, camera, false, true, repeats));
  set(RawQuery::kCameraStream, time_intersect(embree.scene_, camera, true, true, repeats));
  if (!closest.empty()) {
    set(RawQuery::kClosestSingle, time_intersect(embree.scene_, closest, false, false, repeats));
    set(RawQuery::kClosestStream, time_intersect(embree.scene_, closest, true, false, repeats));
  }
  if (!occlusion.empty()) {
    set(RawQuery::kOcclusionSingle, time_occluded(embree.scene_, occlusion, false, repeats));
    set(RawQuery::kOcclusionStream, time_occluded(embree.scene_, occlusion, true, repeats));
  }
  return result;
}

}  // namespace snee
