#include "kernels/physics/snee/manifold_sphere.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>

#include "core/vec3d.h"

namespace snee {

namespace {

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

// The root of f in [a, b], where f(a) and f(b) differ in sign (f returns the value and writes
// the derivative): Newton inside the shrinking bracket, bisecting whenever a step would leave
// it, until a step is below `tolerance` relative to 1 + |u|.
template <class F>
double bracketed_root(const F& f, double a, double b, double fa, double tolerance) {
  double u = 0.5 * (a + b);
  for (int it = 0; it < 100; ++it) {
    double df = 0;
    const double fu = f(u, &df);
    if (fu == 0) break;
    if ((fu < 0) == (fa < 0)) {
      a = u;
      fa = fu;
    } else {
      b = u;
    }
    double next = df != 0 ? u - fu / df : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (next == u || !(b > a)) break;
    const bool converged = std::abs(next - u) <= tolerance * (1.0 + std::abs(u));
    u = next;
    if (converged) break;
  }
  return u;
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
    const double a = knots[i], b = knots[i + 1];
    const double fa = eval(p, a);
    const double fb = eval(p, b);
    if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0))) continue;
    const double u = bracketed_root(
        [&](double x, double* df) {
          *df = eval(dp, x);
          return eval(p, x);
        },
        a, b, fa, 1e-15);
    out.u[out.count++] = u;
  }
  return out;
}

// x in the plane through the centre spanned by the light direction a and x - centre, where
// every refracted ray and chain that reaches x lies: its coordinates (p_a along a, p_b >= 0
// along b) in units of the radius. Not valid outside the sphere or on the axis (p_b = 0),
// where the solutions form a ring, a set of zero volume.
struct LightPlane {
  Vec3d a, b, p;  // p: x - centre in units of the radius
  double p_a = 0, p_b = 0;
  bool valid = false;
};
LightPlane light_plane(Vec3 centre, float radius, Vec3 light, Vec3 x) {
  LightPlane plane;
  plane.a = normalize(Vec3d(light));
  plane.p = (Vec3d(x) - Vec3d(centre)) / static_cast<double>(radius);
  plane.p_a = dot(plane.p, plane.a);
  const Vec3d off_axis = plane.p - plane.p_a * plane.a;
  plane.p_b = length(off_axis);
  plane.valid = plane.p_b > 1e-9 && dot(plane.p, plane.p) < 1.0;
  if (plane.valid) plane.b = off_axis / plane.p_b;
  return plane;
}

// Keeps the exit at unit normal n (in the plane's units, where y = n) if the light arriving
// there from outside along -toward_light refracts (relative index 1 / e) into a ray through p:
// squaring the refraction condition admitted rays that pass through p backwards, or with the
// other sign of the refracted cosine.
void keep_exit(SphereExits& out, Vec3 centre, double r, double e, const Vec3d& n,
               const Vec3d& toward_light, const Vec3d& p) {
  const double c = dot(n, toward_light);
  const double k2 = 1.0 - e * e * (1.0 - c * c);
  if (!(c > 0) || !(k2 > 0)) return;
  const double k = std::sqrt(k2);
  const Vec3d omega_r = -e * toward_light + (e * c - k) * n;
  const Vec3d to_x = p - n;
  const double t = length(to_x);
  if (!(t > 0) || !(dot(to_x / t, omega_r) > 1.0 - 1e-9)) return;
  SphereExit& s = out.exit[static_cast<size_t>(out.count++)];
  s.n = Vec3(n);
  s.y = Vec3(Vec3d(centre) + r * n);
  s.omega_r = Vec3(normalize(omega_r));
  s.t = t * r;
}

// The polynomials in u = tan(phi / 2) that both solvers square their conditions into:
// c = C / D, s = S / D.
const Poly kD = poly({1, 0, 1}), kC = poly({1, 0, -1}), kS = poly({0, 2});

}  // namespace

SphereExits sphere_exits_toward_light(Vec3 centre, float radius, float eta, Vec3 light, Vec3 x) {
  SphereExits out;
  const double e = 1.0 / eta;
  const LightPlane plane = light_plane(centre, radius, light, x);
  if (!plane.valid) return out;
  const double p_a = plane.p_a, p_b = plane.p_b;
  // In the plane (a, b) through the centre, n = (cos phi, sin phi) with phi in (-pi/2, pi/2)
  // (facing the light). The refracted direction is -e a + (e c - k) n with c = cos phi,
  // s = sin phi, k = sqrt(1 - e^2 s^2); it passes through p when
  //   (e c - k) A + e (p_b - s) = 0,  A = p_a s - p_b c  (the 2D cross product).
  // Isolating k and squaring, then u = tan(phi / 2), D = 1 + u^2, C = 1 - u^2, S = 2u, and
  // multiplying by D^4:
  //   (D^2 - e^2 S^2) (A D)^2 - e^2 (C (A D) + p_b D^2 - S D)^2 = 0.
  const Poly AD = add(scale(kS, p_a), scale(kC, p_b), -1.0);
  const Poly D2 = mul(kD, kD);
  const Poly left = mul(add(D2, scale(mul(kS, kS), e * e), -1.0), mul(AD, AD));
  const Poly inner = add(add(mul(kC, AD), scale(D2, p_b)), mul(kS, kD), -1.0);
  const Poly P = add(left, scale(mul(inner, inner), e * e), -1.0);
  const Roots roots = real_roots(P, -1.0, 1.0);
  for (int i = 0; i < roots.count; ++i) {
    const double phi = 2.0 * std::atan(roots.u[i]);
    keep_exit(out, centre, radius, e, std::cos(phi) * plane.a + std::sin(phi) * plane.b, plane.a,
              plane.p);
  }
  return out;
}

SphereExits sphere_exits_toward_point(Vec3 centre, float radius, float eta, Vec3 light_position,
                                      Vec3 x) {
  SphereExits out;
  const double e = 1.0 / eta;
  const Vec3d to_light = (Vec3d(light_position) - Vec3d(centre)) / static_cast<double>(radius);
  const double l = length(to_light);
  if (!(l > 1.0)) return out;
  const LightPlane plane = light_plane(centre, radius, Vec3(to_light / l), x);
  if (!plane.valid) return out;
  const double p_a = plane.p_a, p_b = plane.p_b;
  // The light sits at l a. With n = (cos phi, sin phi) and tangent (-s, c), the refraction
  // keeps the tangential component of the unit direction times e: toward p, -A / |p - n|;
  // arriving from the light, l s / |n - l a|. So
  //   A |n - l a| = -e l s |p - n|,  A = p_a s - p_b c,
  // and squared, with |n - l a|^2 = 1 + l^2 - 2 l c and |p - n|^2 = |p|^2 + 1 - 2 (p_a c + p_b s),
  // times D^3:
  //   (A D)^2 ((1 + l^2) D - 2 l C) - e^2 l^2 S^2 ((|p|^2 + 1) D - 2 (p_a C + p_b S)) = 0,
  // of degree 6. Facing the light needs l c > 1, so |phi| < pi / 2 and u in (-1, 1).
  const Poly AD = add(scale(kS, p_a), scale(kC, p_b), -1.0);
  const Poly to_light2 = add(scale(kD, 1.0 + l * l), scale(kC, 2.0 * l), -1.0);
  const Poly to_x2 = add(scale(kD, dot(plane.p, plane.p) + 1.0),
                         add(scale(kC, 2.0 * p_a), scale(kS, 2.0 * p_b)), -1.0);
  const Poly P =
      add(mul(mul(AD, AD), to_light2), scale(mul(mul(kS, kS), to_x2), e * e * l * l), -1.0);
  const Roots roots = real_roots(P, -1.0, 1.0);
  for (int i = 0; i < roots.count; ++i) {
    const double phi = 2.0 * std::atan(roots.u[i]);
    const Vec3d n = std::cos(phi) * plane.a + std::sin(phi) * plane.b;
    keep_exit(out, centre, radius, e, n, normalize(l * plane.a - n), plane.p);
  }
  return out;
}

double refraction_volume_jacobian(Vec3 n_in, Vec3 light, float eta, double curvature, double t,
                                  double light_distance) {
  const Vec3d n = normalize(Vec3d(n_in)), w = normalize(Vec3d(light));
  const double e = 1.0 / eta, c = dot(n, w);
  const double k2 = 1.0 - e * e * (1.0 - c * c);
  if (!(c > 0) || !(k2 > 0)) return 0.0;
  const double k = std::sqrt(k2);
  const Vec3d omega_r = -e * w + (e * c - k) * n;
  // Moving y along a unit tangent v turns n by curvature * v and, for a light at a finite
  // distance d, the direction toward it by -(v - (v . w) w) / d; so c by dn . w + n . dw, and
  // omega_r by -e dw + (e dc - dk) n + (e c - k) dn with dk = e^2 c dc / k.
  const double inverse_distance = std::isinf(light_distance) ? 0.0 : 1.0 / light_distance;
  const Vec3d v1 =
      normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3d(1, 0, 0)) : cross(n, Vec3d(0, 1, 0)));
  const Vec3d v2 = cross(n, v1);
  const auto dx = [&](const Vec3d& v) {
    const Vec3d dn = curvature * v;
    const Vec3d dw = -inverse_distance * (v - dot(v, w) * w);
    const double dc = dot(dn, w) + dot(n, dw);
    const Vec3d d_omega = -e * dw + (e * dc * (1.0 - e * c / k)) * n + (e * c - k) * dn;
    return v + t * d_omega;
  };
  return std::abs(dot(cross(dx(v1), dx(v2)), omega_r));
}

namespace {

// A value with its derivatives along two surface directions (forward-mode differentiation):
// enough to carry the chain's geometry through refraction and reflections exactly.
struct Dual {
  double v = 0, d1 = 0, d2 = 0;
};
Dual operator+(Dual a, Dual b) {
  return {a.v + b.v, a.d1 + b.d1, a.d2 + b.d2};
}
Dual operator-(Dual a, Dual b) {
  return {a.v - b.v, a.d1 - b.d1, a.d2 - b.d2};
}
Dual operator*(Dual a, Dual b) {
  return {a.v * b.v, a.d1 * b.v + a.v * b.d1, a.d2 * b.v + a.v * b.d2};
}
Dual operator*(double s, Dual a) {
  return {s * a.v, s * a.d1, s * a.d2};
}
Dual inverse(Dual a) {
  const double r = 1.0 / a.v;
  return {r, -a.d1 * r * r, -a.d2 * r * r};
}
Dual sqrt(Dual a) {
  const double r = std::sqrt(a.v);
  return {r, 0.5 * a.d1 / r, 0.5 * a.d2 / r};
}

struct DualVec {
  Dual x, y, z;
};
DualVec operator+(const DualVec& a, const DualVec& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
DualVec operator*(Dual s, const DualVec& a) {
  return {s * a.x, s * a.y, s * a.z};
}
Dual dot(const DualVec& a, const DualVec& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
DualVec operator-(const DualVec& a, const DualVec& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
DualVec constant(const Vec3d& v) {
  return {{v.x, 0, 0}, {v.y, 0, 0}, {v.z, 0, 0}};
}

// The unit sphere's chain from y = n: the refracted direction, then chord after chord, each
// reflection mirroring the direction about the normal (the position itself) at its end.
struct DualChain {
  DualVec last_point, last_direction;
};
DualChain trace_dual_chain(const DualVec& n, const DualVec& a, double e, int reflections) {
  const Dual c = dot(n, a);
  const Dual k = sqrt(Dual{1, 0, 0} - (e * e) * (Dual{1, 0, 0} - c * c));
  DualVec d = (-e) * Dual{1, 0, 0} * a + (e * c - k) * n;
  DualVec p = n;
  for (int i = 0; i < reflections; ++i) {
    p = p + (-2.0 * dot(p, d)) * d;
    d = d + (-2.0 * dot(d, p)) * p;
  }
  return {p, d};
}

Vec3d tangent_to(const Vec3d& n) {
  return normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3d(1, 0, 0)) : cross(n, Vec3d(0, 1, 0)));
}

// The chain's equation in the plane of the light (axis a: its direction, or the direction from
// the centre to a point light at l a) and x (polar radius rho, angle chi from a, in units of the
// sphere's radius), in the angle of incidence theta at the entry. The entry's polar angle is
// phi = theta - asin(sin(theta) / l) (the triangle of centre, light and entry; phi = theta for a
// directional light, 1 / l = 0), so theta in (-pi/2, pi/2) covers every entry that sees the light.
// The ray refracts to the angular momentum L = e sin(theta) about the centre, which every chord
// keeps; after m reflections its direction has the angle psi = phi + (m + 1) pi - (2m + 1)
// asin(L), and x lies on that chord iff its own moment about the centre matches:
// rho sin(psi - chi) = L.
struct ChainEquation {
  double e, rho, chi;
  int m;
  double inverse_l;  // 1 / l: 0 for a directional light
  double value(double theta, double* derivative) const {
    const double s = std::sin(theta), c = std::cos(theta);
    const double moment = e * s;
    const double k = std::sqrt(1.0 - moment * moment);
    const double psi = direction_angle(theta, moment);
    const double dphi = 1.0 - inverse_l * c / std::sqrt(1.0 - inverse_l * inverse_l * s * s);
    const double dpsi = dphi - (2 * m + 1) * e * c / k;
    *derivative = rho * std::cos(psi - chi) * dpsi - e * c;
    return rho * std::sin(psi - chi) - moment;
  }
  double phi(double theta) const { return theta - std::asin(inverse_l * std::sin(theta)); }
  double psi(double theta) const { return direction_angle(theta, e * std::sin(theta)); }
  double direction_angle(double theta, double moment) const {
    return phi(theta) + (m + 1) * kPiD - (2 * m + 1) * std::asin(moment);
  }
  static constexpr double kPiD = std::numbers::pi;
};

// A bound on |F''| over the whole domain, from phi' = 1 - cos(theta) / sqrt(l^2 - sin^2(theta))
// in [0, 1], |phi''| = |sin(theta)| (l^2 - 1) / (l^2 - sin^2(theta))^(3/2) <= 1 / sqrt(l^2 - 1),
// so |psi'| <= 1 + (2m + 1) e / k_min and |psi''| <= 1 / sqrt(l^2 - 1) + (2m + 1) e (1 / k_min +
// e^2 / k_min^3), k_min = sqrt(1 - e^2):
// F'' = rho (-sin(psi - chi) psi'^2 + cos(psi - chi) psi'') + e sin(theta).
double curvature_bound(const ChainEquation& eq) {
  const double k_min = std::sqrt(1.0 - eq.e * eq.e), turns = 2.0 * eq.m + 1.0;
  const double d1 = 1.0 + turns * eq.e / k_min;
  const double d2 = eq.inverse_l / std::sqrt(1.0 - eq.inverse_l * eq.inverse_l) +
                    turns * eq.e * (1.0 / k_min + eq.e * eq.e / (k_min * k_min * k_min));
  return eq.rho * (d1 * d1 + d2) + eq.e;
}

// The roots of the chain equation on (-pi/2, pi/2), none missed: the domain is cut into cells
// (psi turning by at most pi/4 in each, which leaves most cells decided at once; the cuts where
// psi turns back are exact for a directional light, and only save cells otherwise), and each cell
// is split until the bound C on |F''| decides it. With F and F' at both ends of a cell of width
// h, a cell whose ends agree in sign holds no root if the two parabolas |F(end)| +- F'(end) u -
// C u^2 / 2 that bound |F| from below stay positive across it; a cell whose ends differ holds
// exactly one root if F' keeps its sign (|F'(a)| + |F'(b)| > C h with equal signs). Cells below
// 1e-12 rad are a double root on a caustic, a set of zero volume, and yield nothing.
class ChainRootFinder {
 public:
  ChainRootFinder(const ChainEquation& eq, double* roots, int capacity)
      : eq_(eq), c_(curvature_bound(eq)), roots_(roots), capacity_(capacity) {}

  int solve() {
    constexpr double kHalfPi = 0.5 * ChainEquation::kPiD, kEdge = 1e-9;
    std::array<double, 4> knots{-kHalfPi + kEdge, 0, 0, 0};
    int knot_count = 1;
    // For a directional light psi' = 0 where (2m + 1) e cos(theta) = k, i.e. cos^2(theta) = q.
    const double turns2 = (2.0 * eq_.m + 1.0) * (2.0 * eq_.m + 1.0);
    const double q = (1.0 - eq_.e * eq_.e) / (eq_.e * eq_.e * (turns2 - 1.0));
    if (q > 0 && q < 1) {
      const double critical = std::acos(std::sqrt(q));
      knots[knot_count++] = -critical;
      knots[knot_count++] = critical;
    }
    knots[knot_count++] = kHalfPi - kEdge;
    for (int piece = 0; piece + 1 < knot_count; ++piece) {
      const double lo = knots[piece], hi = knots[piece + 1];
      const double turn = std::abs(eq_.psi(hi) - eq_.psi(lo));
      const int cells =
          std::max(2, static_cast<int>(std::ceil(turn / (0.25 * ChainEquation::kPiD))));
      Sample a = sample(lo);
      for (int cell = 1; cell <= cells; ++cell) {
        const Sample b = sample(cell == cells ? hi : lo + (hi - lo) * cell / cells);
        isolate(a, b, 0);
        a = b;
      }
    }
    return count_;
  }

 private:
  struct Sample {
    double phi, f, df;
  };
  Sample sample(double phi) const {
    Sample s{phi, 0, 0};
    s.f = eq_.value(phi, &s.df);
    return s;
  }

  void isolate(const Sample& a, const Sample& b, int depth) {
    const double h = b.phi - a.phi;
    if ((a.f < 0) != (b.f < 0)) {
      if ((a.df > 0) == (b.df > 0) && std::abs(a.df) + std::abs(b.df) > c_ * h) {
        add(bracketed_root([this](double phi, double* df) { return eq_.value(phi, df); }, a.phi,
                           b.phi, a.f, 1e-14));
        return;
      }
    } else {
      // Where the lower bounds of |F| from either end reach zero.
      const double sign = a.f < 0 ? -1.0 : 1.0;
      const double fa = std::abs(a.f), fb = std::abs(b.f);
      const double sa = sign * a.df, sb = -sign * b.df;
      const double reach_a = (sa + std::sqrt(sa * sa + 2.0 * c_ * fa)) / c_;
      const double reach_b = (sb + std::sqrt(sb * sb + 2.0 * c_ * fb)) / c_;
      if (reach_a + reach_b >= h) return;
    }
    if (h < 1e-12 || depth > 60) return;
    const Sample mid = sample(0.5 * (a.phi + b.phi));
    isolate(a, mid, depth + 1);
    isolate(mid, b, depth + 1);
  }

  void add(double root) {
    if (count_ < capacity_) roots_[count_] = root;
    ++count_;
  }

  const ChainEquation& eq_;
  double c_;
  double* roots_;
  int capacity_;
  int count_ = 0;
};

}  // namespace

double sphere_chain_volume_jacobian(Vec3 n_in, Vec3 light, float eta, int reflections,
                                    double t_over_radius, double light_distance_over_radius) {
  const Vec3d n = normalize(Vec3d(n_in)), w = normalize(Vec3d(light));
  const double e = 1.0 / eta, c = dot(n, w);
  if (!(c > 0) || !(1.0 - e * e * (1.0 - c * c) > 0)) return 0.0;
  // On the unit sphere the entry point is its own normal; moving it along a unit tangent v
  // moves it by v, so the surface parameters (u1, u2) have unit area element. A point light's
  // direction turns as the entry moves.
  const Vec3d v1 = tangent_to(n), v2 = cross(n, v1);
  const DualVec y = {{n.x, v1.x, v2.x}, {n.y, v1.y, v2.y}, {n.z, v1.z, v2.z}};
  DualVec toward_light = constant(w);
  if (!std::isinf(light_distance_over_radius)) {
    const DualVec to_light = constant(n + light_distance_over_radius * w) - y;
    toward_light = inverse(sqrt(dot(to_light, to_light))) * to_light;
  }
  const DualChain chain = trace_dual_chain(y, toward_light, e, reflections);
  const DualVec& p = chain.last_point;
  const DualVec& d = chain.last_direction;
  const Vec3d dx1(p.x.d1 + t_over_radius * d.x.d1, p.y.d1 + t_over_radius * d.y.d1,
                  p.z.d1 + t_over_radius * d.z.d1);
  const Vec3d dx2(p.x.d2 + t_over_radius * d.x.d2, p.y.d2 + t_over_radius * d.y.d2,
                  p.z.d2 + t_over_radius * d.z.d2);
  return std::abs(dot(cross(dx1, dx2), Vec3d(d.x.v, d.y.v, d.z.v)));
}

double chain_reflections_probability(int reflections, double search) {
  if (reflections < 1) return 0.0;
  const double m = reflections;
  return search * (2.0 / (m * (m + 1.0)) - 2.0 / ((m + 1.0) * (m + 2.0)));
}

ChainChoice choose_chain_reflections(float u, double search) {
  if (!(u < search)) return {};
  // The tail P(m >= k) = 2 / (k (k + 1)) inverted at v in (0, 1]: the largest m with
  // m (m + 1) <= 2 / v, corrected for rounding either way.
  const double v = 1.0 - u / search;
  const auto tail = [](int k) { return 2.0 / (k * (k + 1.0)); };
  int m = std::max(1, static_cast<int>((-1.0 + std::sqrt(1.0 + 8.0 / v)) / 2.0));
  while (m > 1 && tail(m) < v) --m;
  while (tail(m + 1) >= v) ++m;
  // Where v fell within m's interval (tail(m + 1), tail(m)]: uniform, and independent of m.
  const double leftover = std::clamp((tail(m) - v) / (tail(m) - tail(m + 1)), 0.0, 0x1.fffffep-1);
  return {m, chain_reflections_probability(m, search), leftover};
}

double chain_search_probability(Rgb sigma_t, float radius) {
  const double clearest = std::min({sigma_t.x, sigma_t.y, sigma_t.z});
  return std::clamp(0.5 * std::exp(-clearest * radius), 1.0 / 32.0, 0.5);
}

namespace {

// The chains with m reflections in the light's plane: toward a directional light along
// plane.a (light_distance infinite), or a point light at light_distance radii from the centre
// along plane.a.
SphereChains chains_in_plane(Vec3 centre, float radius, float eta, const LightPlane& plane,
                             double light_distance, int m) {
  SphereChains out;
  const double e = 1.0 / eta, r = radius;
  if (m < 1 || m > kMaxChainReflections || !plane.valid || !(e < 1.0)) return out;
  const Vec3d &a = plane.a, &b = plane.b, &p = plane.p;
  const bool distant = std::isinf(light_distance);
  const ChainEquation eq{e, std::sqrt(plane.p_a * plane.p_a + plane.p_b * plane.p_b),
                         std::atan2(plane.p_b, plane.p_a), m, distant ? 0.0 : 1.0 / light_distance};
  std::array<double, kMaxChainsPerReflectionCount> roots{};
  const int found = ChainRootFinder(eq, roots.data(), kMaxChainsPerReflectionCount).solve();
  out.dropped = std::max(0, found - kMaxChainsPerReflectionCount);
  for (int i = 0; i < std::min(found, kMaxChainsPerReflectionCount); ++i) {
    const double phi = eq.phi(roots[static_cast<size_t>(i)]);
    const Vec3d n = std::cos(phi) * a + std::sin(phi) * b;
    const Vec3d toward_light = distant ? a : normalize(light_distance * a - n);
    const double c = dot(n, toward_light);
    const double k2 = 1.0 - e * e * (1.0 - c * c);
    if (!(c > 0) || !(k2 > 0)) continue;
    const double k = std::sqrt(k2);
    Vec3d d = -e * toward_light + (e * c - k) * n;
    Vec3d q = n;
    SphereChain chain;
    chain.reflections = m;
    for (int j = 0; j < m; ++j) {
      q = q + (-2.0 * dot(q, d)) * d;
      d = d + (-2.0 * dot(d, q)) * q;
      chain.bounce[static_cast<size_t>(j)] = Vec3(Vec3d(centre) + r * q);
    }
    const Vec3d to_x = p - q;
    const double t = length(to_x);
    // The equation (a signed moment) already picks the chord's direction; x must lie on the
    // chord (2k long) and ahead of its start. The direction test only rejects a reversed
    // chord: after many reflections the recomputed chord misses x by 1e-8 or so.
    if (!(t > 0) || !(t < 2.0 * k) || !(dot(to_x / t, d) > 0.99)) continue;
    chain.y = Vec3(Vec3d(centre) + r * n);
    chain.n = Vec3(n);
    chain.omega_last = Vec3(normalize(d));
    chain.t_last = t * r;
    chain.length = (2.0 * k * m + t) * r;
    chain.jacobian =
        sphere_chain_volume_jacobian(Vec3(n), Vec3(toward_light), eta, m, t,
                                     distant ? light_distance : length(light_distance * a - n));
    if (!(chain.jacobian > 0)) continue;
    out.chain[static_cast<size_t>(out.count++)] = chain;
  }
  return out;
}

}  // namespace

SphereChains sphere_reflection_chains_toward_light(Vec3 centre, float radius, float eta, Vec3 light,
                                                   Vec3 x, int reflections) {
  return chains_in_plane(centre, radius, eta, light_plane(centre, radius, light, x),
                         std::numeric_limits<double>::infinity(), reflections);
}

SphereChains sphere_reflection_chains_toward_point(Vec3 centre, float radius, float eta,
                                                   Vec3 light_position, Vec3 x, int reflections) {
  const Vec3d to_light = (Vec3d(light_position) - Vec3d(centre)) / static_cast<double>(radius);
  const double l = length(to_light);
  if (!(l > 1.0)) return {};
  return chains_in_plane(centre, radius, eta, light_plane(centre, radius, Vec3(to_light / l), x), l,
                         reflections);
}

}  // namespace snee
