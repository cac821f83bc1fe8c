#include "kernels/physics/snee/manifold_mesh_point.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/vec3d.h"
#include "scene/memory_budget.h"

namespace snee {

namespace {

constexpr double kPiD = std::numbers::pi;

}  // namespace

bool point_facet_tree_applies(const TriangleMesh& mesh, float eta, Vec3 light_position) {
  if (!(eta > 1.0f)) return false;
  // The winding number of the mesh about the light: the solid angles its triangles subtend
  // there (Van Oosterom and Strackee), summed over 4 pi; 1 inside a closed mesh, 0 outside.
  const Vec3d l(light_position);
  double solid_angle = 0;
  for_each_facet(mesh, [&](const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3d&) {
    const Vec3d a = Vec3d(p0) - l, b = Vec3d(p1) - l, c = Vec3d(p2) - l;
    const double la = length(a), lb = length(b), lc = length(c);
    const double numerator = dot(a, cross(b, c));
    const double denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    solid_angle += 2.0 * std::atan2(numerator, denominator);
  });
  return std::abs(solid_angle) < 2.0 * kPiD;
}

PointFacetTree::PointFacetTree(const TriangleMesh& mesh, float eta, Vec3 light_position, int light)
    : light_position_(light_position), light_(light), e_(1.0 / eta) {
  const Vec3d l(light_position);
  // Reserved in full so the memory is what bytes_at_most promised, not a doubling past it.
  facets_.reserve(mesh.triangle_count());
  std::vector<BallConeTree::Bounds> bounds;
  bounds.reserve(mesh.triangle_count());
  // Each facet's cone. The light's directions toward a facet fill the spherical triangle of its
  // corners' directions, inside the cone around their mean that reaches the farthest corner.
  // Refraction into a denser inside maps directions with a Jacobian whose singular values are e
  // and e cos(incidence) / cos(refraction), both at most e <= 1, so the refracted directions lie
  // within e times that angle of the mean's refraction.
  for_each_facet(mesh, [&](const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3d& n) {
    if (!(dot(n, l - Vec3d(p0)) > 0)) return;
    const Facet f{p0, p1 - p0, p2 - p0, Vec3(n)};
    BallConeTree::Bounds b;
    for (const Vec3& p : {f.p0, f.p0 + f.e1, f.p0 + f.e2}) b.add(Vec3d(p));
    b.centroid = f.p0 + (f.e1 + f.e2) / 3.0f;
    const Vec3d d0 = normalize(Vec3d(f.p0) - l), d1 = normalize(Vec3d(f.p0 + f.e1) - l),
                d2 = normalize(Vec3d(f.p0 + f.e2) - l);
    const Vec3d mean = normalize(d0 + d1 + d2);
    b.axis = refracted_inward(Vec3d(f.n), -mean, 1.0 / e_);
    b.spread =
        e_ * std::max({BallConeTree::angle_between(mean, d0), BallConeTree::angle_between(mean, d1),
                       BallConeTree::angle_between(mean, d2)});
    facets_.push_back(f);
    bounds.push_back(b);
  });
  tree_ = BallConeTree(std::move(bounds));
}

uint64_t PointFacetTree::bytes_at_most(uint64_t triangles) {
  return saturating_add(saturating_multiply(triangles, sizeof(Facet)),
                        BallConeTree::bytes_at_most(triangles));
}

bool PointFacetTree::solve(const Facet& f, const Vec3d& x, MeshExit* exit) const {
  const Vec3d n(f.n), p0(f.p0), l(light_position_);
  const double height_l = dot(l - p0, n), height_x = dot(p0 - x, n);
  if (!(height_l > 0) || !(height_x > 0)) return false;
  // In the plane of incidence: the feet of the light and of x on the facet's plane, and y on the
  // segment between them at distance s from the light's foot. Snell's law,
  //   g(s) = e s / sqrt(s^2 + height_l^2) - (span - s) / sqrt((span - s)^2 + height_x^2) = 0,
  // rises from g(0) < 0 to g(span) > 0: exactly one root, found by bisection.
  const Vec3d foot_l = l - height_l * n, foot_x = x + height_x * n;
  const Vec3d across = foot_x - foot_l;
  const double span = length(across);
  Vec3d y = foot_l;
  if (span > 0) {
    double lo = 0, hi = span;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * span; ++i) {
      const double s = 0.5 * (lo + hi), rest = span - s;
      const double g = e_ * s / std::sqrt(s * s + height_l * height_l) -
                       rest / std::sqrt(rest * rest + height_x * height_x);
      (g < 0 ? lo : hi) = s;
    }
    y = foot_l + (0.5 * (lo + hi) / span) * across;
  }
  // Whether y lies on the facet: its barycentric coordinates in the facet's plane.
  const Vec3d e1(f.e1), e2(f.e2), w = y - p0;
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  const double w1 = dot(w, e1), w2 = dot(w, e2), det = d11 * d22 - d12 * d12;
  const double u = (d22 * w1 - d12 * w2) / det, v = (d11 * w2 - d12 * w1) / det;
  if (!(u >= 0 && v >= 0 && u + v <= 1)) return false;
  const Vec3d to_x = x - y;
  const double t = length(to_x);
  if (!(t > 0)) return false;
  *exit = {Vec3(y), f.n, Vec3(to_x / t), t};
  return true;
}

MeshExits PointFacetTree::exits_toward(Vec3 x_in) const {
  MeshExits out;
  const Vec3d x(x_in);
  tree_.for_each_candidate(x, [&](uint32_t i) {
    MeshExit exit;
    if (!solve(facets_[i], x, &exit)) return;
    if (out.count == kMaxMeshExits) {
      ++out.dropped;
      return;
    }
    out.exit[static_cast<size_t>(out.count++)] = exit;
  });
  return out;
}

}  // namespace snee
