#include "kernels/physics/snee/snee_suffix.h"

#include <cmath>

namespace snee {

namespace {

// Unit direction and length from a to b, in double so nearly coincident points keep accuracy.
Vec3 direction(Vec3 a, Vec3 b, double* length) {
  const double x = static_cast<double>(b.x) - a.x, y = static_cast<double>(b.y) - a.y,
               z = static_cast<double>(b.z) - a.z;
  *length = std::sqrt(x * x + y * y + z * z);
  if (!(*length > 0)) return Vec3();
  return Vec3(static_cast<float>(x / *length), static_cast<float>(y / *length),
              static_cast<float>(z / *length));
}

}  // namespace

SuffixGeometry suffix_geometry(const SneeSuffix& s) {
  SuffixGeometry g;
  g.omega_ik = direction(s.x_i, s.x_k, &g.d);
  g.omega_ij = direction(s.x_i, s.x_j, &g.r_ij);
  g.omega_jk = direction(s.x_j, s.x_k, &g.r_jk);
  g.valid = g.d > 0 && g.r_ij > 0 && g.r_jk > 0;
  g.cos_k_i = dot(s.n_k, g.omega_ik);
  g.cos_k_j = dot(s.n_k, g.omega_jk);
  g.cos_k_j_shading = dot(s.ns_k, g.omega_jk);
  g.cos_o = dot(s.ns_k, s.omega_o);
  g.crosses = g.cos_k_j > 0 && g.cos_k_j_shading > 0 && g.cos_o > 0 && dot(s.n_k, s.omega_o) > 0;
  const Frame frame = Frame::from_normal(s.ns_k);
  g.local_kj = frame.to_local(-g.omega_jk);
  g.local_o = frame.to_local(s.omega_o);
  return g;
}

}  // namespace snee
