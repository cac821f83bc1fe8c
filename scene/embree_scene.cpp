#include "scene/embree_scene.h"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace snee {

namespace {

RTCRayHitNp to_embree(const RayArrays& r, const HitArrays& h) {
  RTCRayHitNp np{};
  np.ray = {r.org_x, r.org_y, r.org_z, r.tnear, r.dir_x, r.dir_y,
            r.dir_z, r.time,  r.tfar,  r.mask,  r.id,    r.flags};
  np.hit.Ng_x = h.ng_x;
  np.hit.Ng_y = h.ng_y;
  np.hit.Ng_z = h.ng_z;
  np.hit.u = h.u;
  np.hit.v = h.v;
  np.hit.primID = h.prim_id;
  np.hit.geomID = h.geom_id;
  np.hit.instID[0] = h.inst_id;
  return np;
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene) : description_(&scene) {
  device_ = rtcNewDevice("verbose=0");
  if (!device_) throw std::runtime_error("cannot create the Embree device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
  // Robust mode selects Embree's watertight (Pluecker) triangle test. The default test is not
  // watertight: a ray through the edge two triangles share (within about one ulp of it) can miss
  // both, so a camera ray slipped into the closed bunny unseen and its path exited twice (gained
  // eta^2), and a ray from inside left it without a crossing (FurnaceCrossing.*).
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);

  face_planes_.resize(scene.shapes.size());
  for (size_t s = 0; s < scene.shapes.size(); ++s) {
    const Shape& shape = scene.shapes[s];
    RTCGeometry geom = nullptr;
    if (shape.kind == ShapeKind::kSphere) {
      has_spheres_ = true;
      geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      v[0] = shape.center.x;
      v[1] = shape.center.y;
      v[2] = shape.center.z;
      v[3] = shape.radius;
    } else {
      const TriangleMesh& mesh = shape.mesh;
      geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                            RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                            mesh.positions.size()));
      for (size_t i = 0; i < mesh.positions.size(); ++i) {
        v[3 * i + 0] = mesh.positions[i].x;
        v[3 * i + 1] = mesh.positions[i].y;
        v[3 * i + 2] = mesh.positions[i].z;
      }
      auto* idx = static_cast<uint32_t*>(
          rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                  3 * sizeof(uint32_t), mesh.triangle_count()));
      std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
      auto& planes = face_planes_[s];
      planes.resize(mesh.triangle_count());
      for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 p0 = mesh.positions[mesh.indices[3 * t]];
        const Vec3 p1 = mesh.positions[mesh.indices[3 * t + 1]];
        const Vec3 p2 = mesh.positions[mesh.indices[3 * t + 2]];
        const Vec3 c = cross(p1 - p0, p2 - p0);
        const float len = length(c);
        const Vec3 n = len > 0 ? c / len : Vec3(0, 0, 1);
        // The plane's distance from the centroid, in double, so that projecting onto it adds
        // no more than the float rounding of the result.
        double distance = 0;
        for (const Vec3& corner : {p0, p1, p2})
          distance +=
              (double{n.x} * corner.x + double{n.y} * corner.y + double{n.z} * corner.z) / 3.0;
        planes[t] = {n, static_cast<float>(distance)};
      }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(s));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene_);
  // Errors are checked once here rather than through a callback: exceptions must not cross
  // Embree's C frames.
  if (const RTCError error = rtcGetDeviceError(device_); error != RTC_ERROR_NONE) {
    throw std::runtime_error("Embree could not build the scene (error code " +
                             std::to_string(int(error)) + ")");
  }
  epsilon_ = ray_clearance(scene);
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::intersect(const RayArrays& rays, const HitArrays& hits, unsigned n,
                            bool coherent) const {
  if (n == 0) return;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags =
      coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  if (n == 1) {
    // A one-ray batch (the megakernel schedule's every query) is a true single-ray query, not
    // a stream of length one.
    RTCRayHit rh{};
    rh.ray = {rays.org_x[0], rays.org_y[0], rays.org_z[0], rays.tnear[0],
              rays.dir_x[0], rays.dir_y[0], rays.dir_z[0], rays.time[0],
              rays.tfar[0],  rays.mask[0],  rays.id[0],    rays.flags[0]};
    rh.hit.geomID = hits.geom_id[0];
    rh.hit.instID[0] = hits.inst_id[0];
    rtcIntersect1(scene_, &context, &rh);
    rays.tfar[0] = rh.ray.tfar;
    hits.ng_x[0] = rh.hit.Ng_x;
    hits.ng_y[0] = rh.hit.Ng_y;
    hits.ng_z[0] = rh.hit.Ng_z;
    hits.u[0] = rh.hit.u;
    hits.v[0] = rh.hit.v;
    hits.prim_id[0] = rh.hit.primID;
    hits.geom_id[0] = rh.hit.geomID;
    hits.inst_id[0] = rh.hit.instID[0];
    settle_sphere_hits(rays, hits, 1);
    return;
  }
  RTCRayHitNp np = to_embree(rays, hits);
  rtcIntersectNp(scene_, &context, &np, n);
  settle_sphere_hits(rays, hits, n);
}

namespace {

// The distance along o + t d to the sphere's surface nearest Embree's `embree_t`: both roots of
// |o + t d - c| = r in double, in the cancellation-free form (they differ by the chord, Embree's
// error is a few ulps), so the result depends on the ray and the sphere alone.
float sphere_hit_distance(const Shape& sphere, Vec3 o, Vec3 d, float embree_t) {
  const double ox = double(o.x) - sphere.center.x, oy = double(o.y) - sphere.center.y,
               oz = double(o.z) - sphere.center.z;
  const double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
  const double b = ox * d.x + oy * d.y + oz * d.z;
  const double c = ox * ox + oy * oy + oz * oz - double(sphere.radius) * sphere.radius;
  const double root = std::sqrt(std::max(0.0, b * b - a * c));
  const double q = -(b + std::copysign(root, b));
  if (!(q != 0.0) || !(a > 0.0)) return embree_t;
  const double t1 = q / a, t2 = c / q;
  return static_cast<float>(std::abs(t1 - embree_t) <= std::abs(t2 - embree_t) ? t1 : t2);
}

}  // namespace

void EmbreeScene::settle_sphere_hits(const RayArrays& rays, const HitArrays& hits,
                                     unsigned n) const {
  if (!has_spheres_) return;
  for (unsigned i = 0; i < n; ++i) {
    const uint32_t geom = hits.geom_id[i];
    if (geom == kInvalidId) continue;
    const Shape& shape = description_->shapes[geom];
    if (shape.kind != ShapeKind::kSphere) continue;
    rays.tfar[i] = sphere_hit_distance(shape, {rays.org_x[i], rays.org_y[i], rays.org_z[i]},
                                       {rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]}, rays.tfar[i]);
  }
}

void EmbreeScene::occluded(const RayArrays& rays, unsigned n) const {
  if (n == 0) return;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  if (n == 1) {
    RTCRay ray{rays.org_x[0], rays.org_y[0], rays.org_z[0], rays.tnear[0],
               rays.dir_x[0], rays.dir_y[0], rays.dir_z[0], rays.time[0],
               rays.tfar[0],  rays.mask[0],  rays.id[0],    rays.flags[0]};
    rtcOccluded1(scene_, &context, &ray);
    rays.tfar[0] = ray.tfar;
    return;
  }
  RTCRayNp np{rays.org_x, rays.org_y, rays.org_z, rays.tnear, rays.dir_x, rays.dir_y,
              rays.dir_z, rays.time,  rays.tfar,  rays.mask,  rays.id,    rays.flags};
  rtcOccludedNp(scene_, &context, &np, n);
}

bool EmbreeScene::intersect1(Vec3 org, Vec3 dir, float tnear, float tfar, float* t, uint32_t* geom,
                             uint32_t* prim) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray = {org.x, org.y, org.z, tnear, dir.x, dir.y, dir.z, 0.0f, tfar, 0xFFFFFFFFu, 0, 0};
  rh.hit.geomID = kInvalidId;
  rh.hit.instID[0] = kInvalidId;
  rtcIntersect1(scene_, &context, &rh);
  *t = rh.ray.tfar;
  *geom = rh.hit.geomID;
  *prim = rh.hit.primID;
  if (*geom != kInvalidId && description_->shapes[*geom].kind == ShapeKind::kSphere)
    *t = sphere_hit_distance(description_->shapes[*geom], org, dir, *t);
  return rh.hit.geomID != kInvalidId;
}

bool EmbreeScene::occluded1(Vec3 org, Vec3 dir, float tnear, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{org.x, org.y, org.z, tnear, dir.x, dir.y, dir.z, 0.0f, tfar, 0xFFFFFFFFu, 0, 0};
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0;
}

Vec3 EmbreeScene::normal(uint32_t geom, uint32_t prim, Vec3 p) const {
  const Shape& shape = description_->shapes[geom];
  if (shape.kind == ShapeKind::kSphere) return normalize(p - shape.center);
  return face_planes_[geom][prim].n;
}

SurfacePoint EmbreeScene::surface_point(uint32_t geom, uint32_t prim, Vec3 approx) const {
  const Shape& shape = description_->shapes[geom];
  if (shape.kind == ShapeKind::kSphere) {
    const Vec3 n = normalize(approx - shape.center);
    return {shape.center + n * shape.radius, n};
  }
  const FacePlane& plane = face_planes_[geom][prim];
  return {approx - plane.n * (dot(plane.n, approx) - plane.distance), plane.n};
}

}  // namespace snee
