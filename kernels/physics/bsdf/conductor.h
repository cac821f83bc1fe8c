// Conductor (metal) reflection in the local frame (normal = +z): the exact Fresnel reflectance
// of a complex index eta + i k per RGB channel over a GGX microfacet distribution with Smith
// separable shadowing (Walter et al. 2007), or a perfect mirror when smooth. Two-sided like the
// diffuse surface: the caller turns the frame so that wo.z > 0, and wi stays on wo's side.
// The colour is split off the scalar lobe, as the diffuse albedo is: sample.f and
// conductor_eval exclude the Fresnel factor, which conductor_fresnel gives for a direction pair.
// Normals are drawn from the distribution of normals visible from wo (ggx.h), so a sample only
// fails where the reflected direction ends below the surface.
#pragma once

#include "kernels/physics/bsdf/dielectric.h"

namespace snee {

struct ConductorParams {
  Rgb eta{0.0f};       // real part of the index, relative to the exterior
  Rgb k{1.0f};         // extinction coefficient
  float alpha = 0.0f;  // GGX alpha; below kSmoothRoughness: a mirror
  bool delta() const { return !(alpha >= kSmoothRoughness); }
};

// wi on wo's side. For a mirror f = 1 / wo.z and pdf = 1, so that f wi.z / pdf = 1.
BsdfSample conductor_sample(const ConductorParams& p, Vec3 wo, Vec2 u);
// The lobe without Fresnel, D G / (4 wo.z wi.z); 0 for a mirror and across the surface.
float conductor_eval(const ConductorParams& p, Vec3 wo, Vec3 wi);
// Pdf of conductor_sample producing wi (solid angle); 0 for a mirror.
float conductor_pdf(const ConductorParams& p, Vec3 wo, Vec3 wi);
// Fresnel reflectance at the half vector of (wo, wi), the factor the lobe leaves out.
Rgb conductor_fresnel(const ConductorParams& p, Vec3 wo, Vec3 wi);

}  // namespace snee
