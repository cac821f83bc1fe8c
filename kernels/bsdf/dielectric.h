// Dielectric interface BSDF, smooth (delta) or rough (GGX, Walter et al. 2007), in the local
// frame of the surface with the *outward* normal = +z. The interior has index `eta` relative
// to the exterior. All directions point away from the surface. Radiance mode: `wo` is the
// camera side, `wi` the light side; transmission carries the (eta_o / eta_i)^2 factor
// (docs/method.md section 4.5). The pdfs include the reflect/transmit selection probability,
// which is the Fresnel reflectance of the sampled (micro)normal. Microfacet normals are drawn
// from D(m) m.z (not visible normals); a normal facing away from wo makes the sample fail, so
// the rough pdfs integrate to the success probability (< 1 at grazing angles).
// An index-matched interface (eta == 1) is treated as smooth whatever alpha: every microfacet
// then refracts straight through, a delta event.
#pragma once

#include <limits>

#include "kernels/sampling.h"

namespace snee {

// Roughness below which an interface is smooth (a delta BSDF). A rough lobe is only as good as
// the half vector rebuilt from a direction pair: after the refraction, the weighted sum and the
// normalisation it is off by about 4 float epsilons of angle, which changes D(h) by up to
// 2 * 4 eps / alpha relative. Holding that to 1% needs alpha >= 800 eps = 9.5e-5; below, the
// rebuilt pdfs (NEE, MIS weights, SNEE's exit pdfs) disagree with the sampled ones, so pt and
// snee drift apart, and near 1e-9 D overflows float (black objects, NaN). A lobe this narrow
// (0.005 degrees) is invisible, so treating it as smooth changes no image.
inline constexpr float kSmoothRoughness = 800.0f * std::numeric_limits<float>::epsilon();

struct DielectricParams {
  float eta = 1.5f;    // interior / exterior
  float alpha = 0.0f;  // below kSmoothRoughness: smooth
  bool smooth() const { return !(alpha >= kSmoothRoughness); }
  bool delta() const { return smooth() || eta == 1.0f; }
};

struct BsdfSample {
  Vec3 wi;        // sampled light-side direction (away from the surface)
  float f = 0;    // BSDF value (for delta lobes: the value that multiplies the delta)
  float pdf = 0;  // solid-angle pdf (for delta lobes: the discrete lobe probability)
  bool transmission = false;
  bool delta = false;
  bool valid = false;
};

// Samples wi given wo. u_lobe picks reflection vs transmission; u picks the microfacet normal.
BsdfSample dielectric_sample(const DielectricParams& p, Vec3 wo, Vec2 u, float u_lobe);
// f(wo <- wi); 0 for a delta interface (delta lobes are never evaluated).
float dielectric_eval(const DielectricParams& p, Vec3 wo, Vec3 wi);
// Pdf of dielectric_sample producing wi from wo (solid angle); 0 for a delta interface.
float dielectric_pdf(const DielectricParams& p, Vec3 wo, Vec3 wi);

// Transmission-only sampling used by SNEE (docs/method.md 4.4): given direction g on one side,
// produce s on the other side by refracting through a GGX-sampled normal (or the macro normal
// when delta). No lobe selection factor. Returns false on TIR, if the normal faces away from g,
// or if s ends on g's side.
bool dielectric_sample_transmission(const DielectricParams& p, Vec3 g, Vec2 u, Vec3* s);
// p^T_btdf(s | g) in solid angle; 0 for invalid pairs and for delta interfaces.
float dielectric_transmission_pdf(const DielectricParams& p, Vec3 g, Vec3 s);

}  // namespace snee
