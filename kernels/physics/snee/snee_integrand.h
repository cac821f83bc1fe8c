// The measurement contribution of a SNEE suffix (docs/method.md 1.3), in the measure of
// suffix_measure(s), with all visibility factors taken as 1 (the caller's shadow rays decide
// them). Deltas are integrated out as in docs/method.md 3.7:
//   A (rough, non-delta light):  F = f_p(w_in.w_ij) T_ij / r_ij^2  sigma_s  f_p(w_ij.w_jk)
//                                    T_jk cos_kj / r_jk^2  f_t(w_kj <- w_o) cos_o L_e
//   B (rough, delta light):      A with L_e replaced by the irradiance E
//   C (smooth, non-delta light): f_t cos_o L_e replaced by eta^2 (1 - F_r) L_e
//   D (smooth, delta light):     f_p T_ij / r_ij^2 sigma_s f_p T_jk (1 - F_r) E cos_o, per
//                                unit area at x_k and unit length along the refracted ray
// f_t is the radiance-mode BTDF with the camera side inside (it carries eta^2).
#pragma once

#include "kernels/physics/snee/snee_suffix.h"

namespace snee {

// `emitted` is L_e(omega_o) for a non-delta light, the irradiance E for a delta light. Per RGB
// channel; the suffix's phase functions, sigma_s(x_j) and transmittances are included,
// sigma_s(x_i) is not (it belongs to the path throughput).
Rgb suffix_integrand(const SneeSuffix& s, Rgb emitted);
// The same with the suffix's geometry already derived (suffix_geometry(s)).
Rgb suffix_integrand(const SneeSuffix& s, const SuffixGeometry& g, Rgb emitted);

}  // namespace snee
