// The one place that talks to Embree: builds the device and scene from the scene description
// and answers batched closest-hit and occlusion queries over rays in Embree's SoA stream layout.
// Keeping every Embree call here means a port to Embree 4 (which dropped streams) touches one
// file. Geometry IDs equal shape indices.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "scene/shape_bounds.h"

namespace snee {

inline constexpr uint32_t kInvalidId = RTC_INVALID_GEOMETRY_ID;

// Non-owning views of SoA ray arrays (each of length >= n, 16-byte aligned).
struct RayArrays {
  float *org_x, *org_y, *org_z, *tnear;
  float *dir_x, *dir_y, *dir_z, *time;
  float* tfar;
  uint32_t *mask, *id, *flags;
};
struct HitArrays {
  float *ng_x, *ng_y, *ng_z, *u, *v;
  uint32_t *prim_id, *geom_id, *inst_id;
};

struct EmbreeThroughput;
class EmbreeScene;
// The raw-traversal benchmark (embree_throughput.h) times Embree's own calls on this scene.
EmbreeThroughput measure_embree_throughput(const Scene& scene, const EmbreeScene& embree,
                                           size_t rays, int repeats);

// A point on a surface and its outward geometric normal (unit).
struct SurfacePoint {
  Vec3 p;
  Vec3 n;
};

class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit for n rays; results in tfar (hit distance) and hits.geom_id/prim_id
  // (kInvalidId on a miss). `coherent` is for camera rays only. A batch of one ray goes to
  // rtcIntersect1 (and rtcOccluded1 below), so the megakernel schedule's one-slot work units
  // issue true single-ray queries. The distance to a sphere is recomputed from the ray and the
  // sphere alone (Embree's single-ray, packet and stream sphere tests round differently, and
  // which one a ray meets depends on the batch it is in), so hits do not depend on the batch.
  void intersect(const RayArrays& rays, const HitArrays& hits, unsigned n, bool coherent) const;
  // Occlusion for n rays: tfar becomes -inf where something lies in [tnear, tfar].
  void occluded(const RayArrays& rays, unsigned n) const;
  // Path-at-a-time queries for the megakernel schedule and tests.
  bool intersect1(Vec3 org, Vec3 dir, float tnear, float tfar, float* t, uint32_t* geom,
                  uint32_t* prim) const;
  bool occluded1(Vec3 org, Vec3 dir, float tnear, float tfar) const;

  // Outward geometric normal (unit) at point p on primitive prim of shape geom.
  Vec3 normal(uint32_t geom, uint32_t prim, Vec3 p) const;
  // The point of primitive prim of shape geom nearest `approx` (a ray's origin + t direction,
  // whose error grows with the ray's length): projected onto the triangle's plane or the sphere,
  // so that it lies within a few ulps of the scene's extent of the surface, however far the ray
  // came from.
  SurfacePoint surface_point(uint32_t geom, uint32_t prim, Vec3 approx) const;
  // Clearance that ray origins keep from a surface: a bound on the floating-point error of a
  // surface point from surface_point and of Embree's own sign of the distance to the surface
  // (ray_clearance in scene/shape_bounds.h: kClearanceUlps ulps of the scene's extent; measured in
  // docs/performance.md). A ray that starts this far from a surface on one side never finds that
  // surface behind it, nor misses it ahead.
  float ray_epsilon() const { return epsilon_; }

 private:
  friend EmbreeThroughput measure_embree_throughput(const Scene&, const EmbreeScene&, size_t, int);

  void settle_sphere_hits(const RayArrays& rays, const HitArrays& hits, unsigned n) const;

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  const Scene* description_;
  struct FacePlane {
    Vec3 n;          // outward unit normal
    float distance;  // dot(n, p) for every point p of the face
  };
  std::vector<std::vector<FacePlane>> face_planes_;  // per mesh shape
  float epsilon_ = 1e-4f;
  bool has_spheres_ = false;
};

}  // namespace snee
