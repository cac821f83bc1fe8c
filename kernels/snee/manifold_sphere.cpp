#include "kernels/snee/manifold_sphere.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace snee {

namespace {

// The solve runs in double: the polynomial's roots near grazing exits are ill-conditioned in
// float.
struct Vec3d {
  double x = 0, y = 0, z = 0;
  Vec3d() = default;
  Vec3d(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit Vec3d(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
  explicit operator Vec3() const {
    return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
  }
  Vec3d operator+(const Vec3d& b) const { return {x + b.x, y + b.y, z + b.z}; }
  Vec3d operator-(const Vec3d& b) const { return {x - b.x, y - b.y, z - b.z}; }
  Vec3d operator-() const { return {-x, -y, -z}; }
  Vec3d operator/(double s) const { return {x / s, y / s, z / s}; }
};
Vec3d operator*(double s, const Vec3d& v) {
  return {s * v.x, s * v.y, s * v.z};
}
double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double length(const Vec3d& v) {
  return std::sqrt(dot(v, v));
}
Vec3d normalize(const Vec3d& v) {
  return v / length(v);
}

// A polynomial of degree <= 8 in u, coefficient i of u^i.
struct Poly {
  std::array<double, 9> c{};
  int degree = 0;
};

Poly poly(std::initializer_list<double> coefficients) {
  Poly p;
  int i = 0;
  for (const double v : coefficients) p.c[static_cast<size_t>(i++)] = v;
  p.degree = i - 1;
  return p;
}

Poly add(const Poly& a, const Poly& b, double sb = 1.0) {
  Poly r;
  r.degree = std::max(a.degree, b.degree);
  for (int i = 0; i <= r.degree; ++i) r.c[i] = a.c[i] + sb * b.c[i];
  return r;
}

Poly mul(const Poly& a, const Poly& b) {
  Poly r;
  r.degree = a.degree + b.degree;
  for (int i = 0; i <= a.degree; ++i)
    for (int j = 0; j <= b.degree; ++j) r.c[i + j] += a.c[i] * b.c[j];
  return r;
}

Poly scale(const Poly& a, double s) {
  Poly r = a;
  for (int i = 0; i <= r.degree; ++i) r.c[i] *= s;
  return r;
}

double eval(const Poly& p, double u) {
  double v = 0;
  for (int i = p.degree; i >= 0; --i) v = v * u + p.c[i];
  return v;
}

Poly derivative(const Poly& p) {
  Poly r;
  r.degree = std::max(0, p.degree - 1);
  for (int i = 1; i <= p.degree; ++i) r.c[i - 1] = i * p.c[i];
  return r;
}

// Drops exactly vanishing leading coefficients (a lower degree changes nothing below).
Poly trimmed(Poly p) {
  while (p.degree > 0 && p.c[p.degree] == 0) --p.degree;
  return p;
}

struct Roots {
  std::array<double, 8> u{};
  int count = 0;
};

// The simple real roots of p in the open interval (lo, hi): between consecutive roots of p' the
// polynomial is monotonic, so each sign change brackets exactly one root, found by bisection to
// double precision. A root where p' also vanishes (two solutions merging, on the caustic) is a
// set of zero volume and is not reported.
Roots real_roots(const Poly& p_in, double lo, double hi) {
  const Poly p = trimmed(p_in);
  Roots out;
  if (p.degree == 0) return out;
  std::array<double, 10> knots{};
  int knot_count = 0;
  knots[knot_count++] = lo;
  if (p.degree > 1) {
    const Roots critical = real_roots(derivative(p), lo, hi);
    for (int i = 0; i < critical.count; ++i) knots[knot_count++] = critical.u[i];
  }
  knots[knot_count++] = hi;
  const Poly dp = derivative(p);
  for (int i = 0; i + 1 < knot_count; ++i) {
    double a = knots[i], b = knots[i + 1];
    double fa = eval(p, a);
    const double fb = eval(p, b);
    if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0))) continue;
    // Newton inside the shrinking bracket, bisecting whenever a step would leave it.
    double u = 0.5 * (a + b);
    for (int it = 0; it < 100; ++it) {
      const double f = eval(p, u);
      if (f == 0) break;
      if ((f < 0) == (fa < 0)) {
        a = u;
        fa = f;
      } else {
        b = u;
      }
      const double df = eval(dp, u);
      double next = df != 0 ? u - f / df : 0.5 * (a + b);
      if (!(next > a && next < b)) next = 0.5 * (a + b);
      if (next == u || b - a <= 0) break;
      const bool converged = std::abs(next - u) <= 1e-15 * (1.0 + std::abs(u));
      u = next;
      if (converged) break;
    }
    out.u[out.count++] = u;
  }
  return out;
}

}  // namespace

SphereExits sphere_exits_toward_light(Vec3 centre, float radius, float eta, Vec3 light, Vec3 x) {
  SphereExits out;
  const double e = 1.0 / eta, r = radius;
  const Vec3d a = normalize(Vec3d(light));
  const Vec3d p = (Vec3d(x) - Vec3d(centre)) / r;
  const double p_a = dot(p, a);
  const Vec3d off_axis = p - p_a * a;
  const double p_b = length(off_axis);
  if (!(p_b > 1e-9) || !(dot(p, p) < 1.0)) return out;
  const Vec3d b = off_axis / p_b;
  // In the plane (a, b) through the centre, n = (cos phi, sin phi) with phi in (-pi/2, pi/2)
  // (facing the light). The refracted direction is -e a + (e c - k) n with c = cos phi,
  // s = sin phi, k = sqrt(1 - e^2 s^2); it passes through p when
  //   (e c - k) A + e (p_b - s) = 0,  A = p_a s - p_b c  (the 2D cross product).
  // Isolating k and squaring, then u = tan(phi / 2), c = (1 - u^2) / D, s = 2u / D, D = 1 + u^2,
  // and multiplying by D^4:
  //   (D^2 - e^2 S^2) (A D)^2 - e^2 (C (A D) + p_b D^2 - S D)^2 = 0,  C = 1 - u^2, S = 2u.
  const Poly D = poly({1, 0, 1}), C = poly({1, 0, -1}), S = poly({0, 2});
  const Poly AD = add(scale(S, p_a), scale(C, p_b), -1.0);
  const Poly D2 = mul(D, D);
  const Poly left = mul(add(D2, scale(mul(S, S), e * e), -1.0), mul(AD, AD));
  const Poly inner = add(add(mul(C, AD), scale(D2, p_b)), mul(S, D), -1.0);
  const Poly P = add(left, scale(mul(inner, inner), e * e), -1.0);
  const Roots roots = real_roots(P, -1.0, 1.0);
  for (int i = 0; i < roots.count; ++i) {
    const double phi = 2.0 * std::atan(roots.u[i]);
    const Vec3d n = std::cos(phi) * a + std::sin(phi) * b;
    const double c = dot(n, a);
    const double k2 = 1.0 - e * e * (1.0 - c * c);
    if (!(c > 0) || !(k2 > 0)) continue;
    const double k = std::sqrt(k2);
    const Vec3d omega_r = -e * a + (e * c - k) * n;
    const Vec3d to_x = p - n;
    const double t = length(to_x);
    if (!(t > 0)) continue;
    // Squaring admitted the rays that pass through p backwards or with the other sign of k.
    if (!(dot(to_x / t, omega_r) > 1.0 - 1e-9)) continue;
    SphereExit& s = out.exit[static_cast<size_t>(out.count++)];
    s.n = Vec3(n);
    s.y = Vec3(Vec3d(centre) + r * n);
    s.omega_r = Vec3(normalize(omega_r));
    s.t = t * r;
  }
  return out;
}

double refraction_volume_jacobian(Vec3 n_in, Vec3 light, float eta, double curvature, double t) {
  const Vec3d n = normalize(Vec3d(n_in)), w = normalize(Vec3d(light));
  const double e = 1.0 / eta, c = dot(n, w);
  const double k2 = 1.0 - e * e * (1.0 - c * c);
  if (!(c > 0) || !(k2 > 0)) return 0.0;
  const double k = std::sqrt(k2);
  const Vec3d omega_r = -e * w + (e * c - k) * n;
  // Moving y along a unit tangent v turns n by curvature * v, so c by curvature (v . w), and
  // omega_r by d(e c - k) n + (e c - k) dn with dk = e^2 c dc / k.
  const Vec3d v1 =
      normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3d(1, 0, 0)) : cross(n, Vec3d(0, 1, 0)));
  const Vec3d v2 = cross(n, v1);
  const auto dx = [&](const Vec3d& v) {
    const Vec3d dn = curvature * v;
    const double dc = dot(dn, w);
    const Vec3d d_omega = (e * dc * (1.0 - e * c / k)) * n + (e * c - k) * dn;
    return v + t * d_omega;
  };
  return std::abs(dot(cross(dx(v1), dx(v2)), omega_r));
}

}  // namespace snee
