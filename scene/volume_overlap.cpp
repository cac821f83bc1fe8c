#include "scene/volume_overlap.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "scene/embree_scene.h"

namespace snee {
namespace {

struct Box {
  Vec3 lo{kInfinity};
  Vec3 hi{-kInfinity};
  void add(Vec3 p) {
    lo = vmin(lo, p);
    hi = vmax(hi, p);
  }
  bool overlaps(const Box& b, float tolerance) const {
    for (int a = 0; a < 3; ++a) {
      if (lo[a] > b.hi[a] + tolerance || b.lo[a] > hi[a] + tolerance) return false;
    }
    return true;
  }
};

Box box_of(const Shape& shape) {
  Box box;
  if (shape.kind == ShapeKind::kSphere) {
    box.add(shape.center - Vec3(shape.radius));
    box.add(shape.center + Vec3(shape.radius));
  } else {
    for (const Vec3& p : shape.mesh.positions) box.add(p);
  }
  return box;
}

struct Triangle {
  Vec3 a, b, c;
};
Triangle triangle(const TriangleMesh& mesh, size_t t) {
  const uint32_t* i = &mesh.indices[3 * t];
  return {mesh.positions[i[0]], mesh.positions[i[1]], mesh.positions[i[2]]};
}

// Nearest point of a triangle to p, by which of the triangle's Voronoi regions (three vertices,
// three edges, the face) holds p.
Vec3 closest_point(const Triangle& tri, Vec3 p) {
  const Vec3 ab = tri.b - tri.a, ac = tri.c - tri.a, ap = p - tri.a;
  const float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return tri.a;
  const Vec3 bp = p - tri.b;
  const float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return tri.b;
  const Vec3 cp = p - tri.c;
  const float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return tri.c;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return tri.a + ab * (d1 / (d1 - d3));
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return tri.a + ac * (d2 / (d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return tri.b + (tri.c - tri.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const float denominator = 1.0f / (va + vb + vc);
  return tri.a + ab * (vb * denominator) + ac * (vc * denominator);
}

// Generalized winding number of a closed mesh at p: the solid angle its triangles subtend,
// over 4 pi (1 inside, 0 outside, whatever the mesh's size or shape, and robust to the
// rounding that makes ray-parity tests fail where a ray grazes an edge). Per triangle the solid
// angle is van Oosterom and Strackee's formula.
double winding_number(const TriangleMesh& mesh, Vec3 p) {
  double total = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle tri = triangle(mesh, t);
    const Vec3 a = tri.a - p, b = tri.b - p, c = tri.c - p;
    const double la = length(a), lb = length(b), lc = length(c);
    const double numerator = dot(a, cross(b, c));
    const double denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

// Whether a shape holds p inside. Open meshes hold nothing.
bool holds(const Shape& shape, Vec3 p) {
  if (shape.kind == ShapeKind::kSphere) return length(p - shape.center) < shape.radius;
  return shape.closed && winding_number(shape.mesh, p) > 0.5;
}

// Whether `outer` holds the mesh `inner`, given that their surfaces do not cross: a vertex
// decides. A vertex on the outer surface has a winding number near 1/2, so up to eight vertices
// spread over the mesh are asked until one is clearly inside or outside.
bool holds_mesh(const Shape& outer, const TriangleMesh& inner) {
  const size_t n = inner.positions.size();
  const size_t step = std::max<size_t>(1, n / 8);
  for (size_t i = 0; i < n; i += step) {
    const Vec3 p = inner.positions[i];
    if (outer.kind == ShapeKind::kSphere) {
      const float d = length(p - outer.center) - outer.radius;
      if (std::fabs(d) > 1e-4f * outer.radius) return d < 0;
    } else {
      if (!outer.closed) return false;
      const double w = winding_number(outer.mesh, p);
      if (std::fabs(w - 0.5) > 0.25) return w > 0.5;
    }
  }
  return false;
}

enum class Relation { kApart, kCrossing, kFirstHoldsSecond, kSecondHoldsFirst };

Relation spheres(const Shape& a, const Shape& b, float tolerance) {
  const float d = length(a.center - b.center);
  if (d >= a.radius + b.radius - tolerance) return Relation::kApart;
  if (d > std::fabs(a.radius - b.radius) + tolerance) return Relation::kCrossing;
  return a.radius >= b.radius ? Relation::kFirstHoldsSecond : Relation::kSecondHoldsFirst;
}

// A sphere and a mesh. A triangle crosses the sphere's surface when some of it lies inside and
// some outside (it is connected); with no crossing, a triangle inside means the mesh (or a part
// of it) is inside the sphere, and else the sphere's centre tells whether the mesh holds it.
Relation sphere_and_mesh(const Shape& sphere, const Shape& mesh, float tolerance) {
  bool some_inside = false;
  for (size_t t = 0; t < mesh.mesh.triangle_count(); ++t) {
    const Triangle tri = triangle(mesh.mesh, t);
    const float nearest = length(closest_point(tri, sphere.center) - sphere.center);
    if (nearest >= sphere.radius - tolerance) continue;
    const float farthest = std::max({length(tri.a - sphere.center), length(tri.b - sphere.center),
                                     length(tri.c - sphere.center)});
    if (farthest > sphere.radius + tolerance) return Relation::kCrossing;
    some_inside = true;
  }
  if (some_inside) return Relation::kFirstHoldsSecond;
  return holds(mesh, sphere.center) ? Relation::kSecondHoldsFirst : Relation::kApart;
}

// Two triangle meshes' surfaces cross exactly when an edge of one passes through a triangle of
// the other, so each mesh's edges near the other are traced as segments through the scene.
class EdgeTracer {
 public:
  explicit EdgeTracer(const Scene& scene) : scene_(scene) {}

  // Whether an edge of shape `from` passes through shape `to` more than `tolerance` away from
  // the edge's ends.
  bool edges_cross(int from, int to, const Box& to_box, float tolerance) {
    if (!embree_) embree_ = std::make_unique<EmbreeScene>(scene_);
    const TriangleMesh& mesh = scene_.shapes[from].mesh;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle tri = triangle(mesh, t);
      const Vec3 corners[3] = {tri.a, tri.b, tri.c};
      for (int e = 0; e < 3; ++e) {
        if (segment_hits(corners[e], corners[(e + 1) % 3], to, to_box, tolerance)) return true;
      }
    }
    return false;
  }

 private:
  bool segment_hits(Vec3 p, Vec3 q, int to, const Box& to_box, float tolerance) const {
    Box segment;
    segment.add(p);
    segment.add(q);
    if (!segment.overlaps(to_box, tolerance)) return false;
    const float edge_length = length(q - p);
    if (!(edge_length > 2 * tolerance)) return false;
    const Vec3 d = (q - p) / edge_length;
    // Hits on other shapes are stepped over; a handful is plenty for one edge.
    constexpr int kMaxHits = 16;
    float t_near = tolerance;
    for (int i = 0; i < kMaxHits; ++i) {
      float t;
      uint32_t geom, prim;
      if (!embree_->intersect1(p, d, t_near, edge_length - tolerance, &t, &geom, &prim)) {
        return false;
      }
      if (static_cast<int>(geom) == to) return true;
      t_near = std::max(t_near, t) + tolerance;
    }
    return false;
  }

  const Scene& scene_;
  std::unique_ptr<EmbreeScene> embree_;
};

Relation meshes(const Scene& scene, int a, int b, const Box& box_a, const Box& box_b,
                float tolerance, EdgeTracer& tracer) {
  if (tracer.edges_cross(a, b, box_b, tolerance) || tracer.edges_cross(b, a, box_a, tolerance)) {
    return Relation::kCrossing;
  }
  const Shape& sa = scene.shapes[a];
  const Shape& sb = scene.shapes[b];
  if (holds_mesh(sa, sb.mesh)) return Relation::kFirstHoldsSecond;
  if (holds_mesh(sb, sa.mesh)) return Relation::kSecondHoldsFirst;
  return Relation::kApart;
}

Relation relate(const Scene& scene, int a, int b, const std::vector<Box>& boxes, float tolerance,
                EdgeTracer& tracer) {
  const Shape& sa = scene.shapes[a];
  const Shape& sb = scene.shapes[b];
  const bool sphere_a = sa.kind == ShapeKind::kSphere;
  const bool sphere_b = sb.kind == ShapeKind::kSphere;
  if (sphere_a && sphere_b) return spheres(sa, sb, tolerance);
  if (sphere_a) return sphere_and_mesh(sa, sb, tolerance);
  if (sphere_b) {
    const Relation r = sphere_and_mesh(sb, sa, tolerance);
    if (r == Relation::kFirstHoldsSecond) return Relation::kSecondHoldsFirst;
    if (r == Relation::kSecondHoldsFirst) return Relation::kFirstHoldsSecond;
    return r;
  }
  return meshes(scene, a, b, boxes[a], boxes[b], tolerance, tracer);
}

}  // namespace

bool is_volume(const Scene& scene, int shape) {
  const Shape& s = scene.shapes[shape];
  if (s.kind == ShapeKind::kMesh && !s.closed) return false;
  return s.interior_medium >= 0 || scene.materials[s.material].kind == MaterialKind::kDielectric;
}

std::vector<VolumeContact> find_volume_contacts(const Scene& scene) {
  const int n = static_cast<int>(scene.shapes.size());
  std::vector<bool> volume(n);
  int volumes = 0;
  for (int i = 0; i < n; ++i) {
    volume[i] = is_volume(scene, i);
    volumes += volume[i];
  }
  std::vector<VolumeContact> contacts;
  if (volumes == 0 || n < 2) return contacts;

  std::vector<Box> boxes(n);
  Box all;
  for (int i = 0; i < n; ++i) {
    boxes[i] = box_of(scene.shapes[i]);
    all.add(boxes[i].lo);
    all.add(boxes[i].hi);
  }
  const float tolerance = 1e-6f * max_component(all.hi - all.lo);

  EdgeTracer tracer(scene);
  for (int v = 0; v < n; ++v) {
    if (!volume[v]) continue;
    for (int s = 0; s < n; ++s) {
      // A pair of volumes is looked at once, from the first of them.
      if (s == v || (volume[s] && s < v)) continue;
      if (!boxes[v].overlaps(boxes[s], tolerance)) continue;
      switch (relate(scene, v, s, boxes, tolerance, tracer)) {
        case Relation::kApart:
          break;
        case Relation::kCrossing:
          contacts.push_back({v, s, false});
          break;
        case Relation::kFirstHoldsSecond:
          contacts.push_back({v, s, true});
          break;
        case Relation::kSecondHoldsFirst:
          // A volume inside an opaque closed shell is fine: only a medium can be entered.
          if (volume[s]) contacts.push_back({s, v, true});
          break;
      }
    }
  }
  return contacts;
}

}  // namespace snee
