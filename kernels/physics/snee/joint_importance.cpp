#include "kernels/physics/snee/joint_importance.h"

#include <cmath>
#include <numbers>

#include "core/vec3d.h"
#include "kernels/physics/medium/henyey_greenstein.h"

namespace snee {

namespace {

constexpr double kPiD = std::numbers::pi;

// Probability of the geometric direction lobe; the phase lobe takes the rest.
double geometric_lobe_weight(const JointImportance& j) {
  return j.g == 0 ? 1.0 : j.c_joint;
}

// Direction density at x_i, given the direction's angle gamma to x_k and its cosine mu with the
// incoming direction (for the phase lobe).
double direction_density(const JointImportance& j, double gamma, double sin_gamma, double mu) {
  const double c = geometric_lobe_weight(j);
  double p = c * (kPiD - gamma) / (kPiD * kPiD * kPiD * sin_gamma);
  if (c < 1) p += (1 - c) * hg_phase(static_cast<float>(mu), j.g);
  return p;
}

// A direction whose half-line passes x_k at angle 0 or pi has no equiangular parametrisation
// (the closest approach h vanishes); such directions are never sampled and have density 0.
bool usable_angle(double gamma, double sin_gamma) {
  return sin_gamma > 0 && gamma < kPiD;
}

}  // namespace

JointImportanceSample joint_importance_sample(
    const JointImportance& j, std::span<const float, kJointImportanceDimensions> u) {
  const Vec3d ik = Vec3d(j.x_k) - Vec3d(j.x_i);
  const double d = length(ik);
  if (!(d > 0)) return {};
  const Vec3d a = ik * (1 / d);

  Vec3d w;
  double gamma, sin_gamma;
  if (u[0] < geometric_lobe_weight(j)) {
    // Inverse CDF of p(gamma) = 2 (pi - gamma) / pi^2.
    gamma = kPiD * (1 - std::sqrt(1 - static_cast<double>(u[1])));
    sin_gamma = std::sin(gamma);
    const double phi = 2 * kPiD * u[2];
    const Frame frame = Frame::from_normal(normalize(Vec3(a.x, a.y, a.z)));
    const Vec3d s = Vec3d(frame.s), t = Vec3d(frame.t);
    const double cos_gamma = std::cos(gamma), cp = std::cos(phi), sp = std::sin(phi);
    w = {cos_gamma * a.x + sin_gamma * (cp * s.x + sp * t.x),
         cos_gamma * a.y + sin_gamma * (cp * s.y + sp * t.y),
         cos_gamma * a.z + sin_gamma * (cp * s.z + sp * t.z)};
  } else {
    float phase_pdf;
    w = Vec3d(hg_sample(j.omega_in, j.g, Vec2{u[1], u[2]}, &phase_pdf));
    w = w * (1 / length(w));
    sin_gamma = length(cross(w, a));
    gamma = std::atan2(sin_gamma, dot(w, a));
  }
  if (!usable_angle(gamma, sin_gamma)) return {};

  // Equiangular step toward x_k along x_i + s w: closest approach at s = delta, distance h;
  // the angle seen from x_k runs over [gamma - pi/2, pi/2) as s runs over [0, inf).
  const double delta = d * std::cos(gamma), h = d * sin_gamma;
  const double theta = gamma - 0.5 * kPiD + u[3] * (kPiD - gamma);
  const double s = delta + h * std::tan(theta);
  if (!(s > 0) || !std::isfinite(s)) return {};
  const Vec3 x_j(static_cast<float>(j.x_i.x + s * w.x), static_cast<float>(j.x_i.y + s * w.y),
                 static_cast<float>(j.x_i.z + s * w.z));
  if (!is_finite(x_j)) return {};

  const double r_jk2 = h * h + (s - delta) * (s - delta);
  const double mu = dot(Vec3d(j.omega_in), w);
  const double pdf =
      direction_density(j, gamma, sin_gamma, mu) * h / ((kPiD - gamma) * r_jk2) / (s * s);
  return {x_j, static_cast<float>(pdf), pdf > 0};
}

float joint_importance_pdf(const JointImportance& j, Vec3 x_j) {
  const Vec3d xi = Vec3d(j.x_i), xj = Vec3d(x_j), xk = Vec3d(j.x_k);
  const Vec3d ik = xk - xi, ij = xj - xi;
  const double d = length(ik), s = length(ij);
  if (!(d > 0) || !(s > 0)) return 0.0f;
  const Vec3d a = ik * (1 / d), w = ij * (1 / s);
  const double sin_gamma = length(cross(w, a));
  const double gamma = std::atan2(sin_gamma, dot(w, a));
  if (!usable_angle(gamma, sin_gamma)) return 0.0f;
  const Vec3d jk = xk - xj;
  const double r_jk2 = dot(jk, jk);
  if (!(r_jk2 > 0)) return 0.0f;
  const double h = d * sin_gamma;
  const double mu = dot(Vec3d(j.omega_in), w);
  return static_cast<float>(direction_density(j, gamma, sin_gamma, mu) * h /
                            ((kPiD - gamma) * r_jk2) / (s * s));
}

}  // namespace snee
