#include "kernels/physics/snee/snee_integrand.h"

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/henyey_greenstein.h"

namespace snee {

Rgb suffix_integrand(const SneeSuffix& s, Rgb emitted) {
  return suffix_integrand(s, suffix_geometry(s), emitted);
}

Rgb suffix_integrand(const SneeSuffix& s, const SuffixGeometry& g, Rgb emitted) {
  if (!g.valid || !g.crosses) return Rgb(0.0f);
  const double phases = static_cast<double>(hg_phase(dot(s.omega_in, g.omega_ij), s.medium.g)) *
                        hg_phase(dot(g.omega_ij, g.omega_jk), s.medium.g);
  const Rgb attenuation = s.medium.sigma_s *
                          transmittance(s.medium.sigma_t, static_cast<float>(g.r_ij)) *
                          transmittance(s.medium.sigma_t, static_cast<float>(g.r_jk));
  const double first_segment = phases / (g.r_ij * g.r_ij);
  const double second_segment = g.cos_k_j / (g.r_jk * g.r_jk);
  const double eta = s.interface.eta;
  double exit = 0;
  switch (suffix_measure(s)) {
    case SuffixMeasure::kFull:
    case SuffixMeasure::kDeltaLight:
      exit = second_segment * dielectric_eval(s.interface, g.local_kj, g.local_o) * g.cos_o;
      break;
    case SuffixMeasure::kDeltaInterface:
      exit = second_segment * eta * eta *
             (1.0 - fresnel_dielectric(static_cast<float>(g.cos_o), s.interface.eta));
      break;
    case SuffixMeasure::kDeltaBoth:
      // dV(x_j) = cos_k_j dA(x_k) dt by the geometric normal, while the refraction that maps
      // omega_o to omega_kj turns about the shading normal (docs/method.md 3.7, 4.9).
      exit = (1.0 - fresnel_dielectric(static_cast<float>(g.cos_o), s.interface.eta)) * g.cos_o *
             (g.cos_k_j / g.cos_k_j_shading);
      break;
  }
  return attenuation * emitted * static_cast<float>(first_segment * exit);
}

}  // namespace snee
