#include "kernels/physics/snee/distance_samplers.h"

#include <cmath>
#include <numbers>

#include "kernels/physics/medium/free_flight.h"

namespace snee {

namespace {

// The ray seen from c: closest approach at t = delta, at distance h. Angles are measured at c
// from the closest-approach point, so t in [0, inf) maps to theta in [theta_a, pi/2).
struct EquiangularGeometry {
  double delta = 0, h = 0, theta_a = 0;
  double angle_range() const { return 0.5 * std::numbers::pi - theta_a; }
  bool degenerate() const { return !(h > 0) || !(angle_range() > 0); }
};

EquiangularGeometry equiangular_geometry(Vec3 o, Vec3 w, Vec3 c) {
  const double vx = c.x - o.x, vy = c.y - o.y, vz = c.z - o.z;
  const double delta = vx * w.x + vy * w.y + vz * w.z;
  const double px = vx - delta * w.x, py = vy - delta * w.y, pz = vz - delta * w.z;
  const double h = std::sqrt(px * px + py * py + pz * pz);
  return {delta, h, std::atan2(-delta, h)};
}

double equiangular_density(const EquiangularGeometry& g, double t) {
  const double r = t - g.delta;
  return g.h / (g.angle_range() * (g.h * g.h + r * r));
}

}  // namespace

DistanceSample equiangular_sample(Vec3 o, Vec3 w, Vec3 c, float u) {
  const EquiangularGeometry g = equiangular_geometry(o, w, c);
  if (g.degenerate()) return {};
  const double theta = g.theta_a + static_cast<double>(u) * g.angle_range();
  const double t = g.delta + g.h * std::tan(theta);
  const float tf = static_cast<float>(t);
  if (!(tf >= 0) || !std::isfinite(tf)) return {};
  return {tf, static_cast<float>(equiangular_density(g, t)), true};
}

float equiangular_pdf(Vec3 o, Vec3 w, Vec3 c, float t) {
  const EquiangularGeometry g = equiangular_geometry(o, w, c);
  if (g.degenerate() || !(t >= 0)) return 0.0f;
  return static_cast<float>(equiangular_density(g, t));
}

DistanceSample distance_mixture_sample(const DistanceMixture& m, float u_technique, float u_channel,
                                       float u) {
  float t = 0;
  if (u_technique < m.c_exponential) {
    t = free_flight_sample(m.sigma_t, u_channel, u);
  } else {
    const DistanceSample s = equiangular_sample(m.o, m.w, m.c, u);
    if (!s.valid) return {};
    t = s.t;
  }
  if (!(t >= 0) || !std::isfinite(t)) return {};
  const float pdf = distance_mixture_pdf(m, t);
  if (!(pdf > 0)) return {};
  return {t, pdf, true};
}

float distance_mixture_pdf(const DistanceMixture& m, float t) {
  if (!(t >= 0)) return 0.0f;
  const double exponential = m.c_exponential > 0 ? free_flight_pdf(m.sigma_t, t) : 0.0;
  const double equiangular = m.c_exponential < 1 ? equiangular_pdf(m.o, m.w, m.c, t) : 0.0;
  return static_cast<float>(m.c_exponential * exponential + (1.0 - m.c_exponential) * equiangular);
}

}  // namespace snee
