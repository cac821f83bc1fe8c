// Complex indices of refraction for the conductor material: the named metals of the scene
// format, and the conversion from a glTF base colour.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/math.h"

namespace snee {

struct ComplexIor {
  Rgb eta;  // real part, relative to vacuum (air)
  Rgb k;    // extinction coefficient
};

// "gold", "silver", "copper", "aluminium"; nullopt for any other name.
std::optional<ComplexIor> find_metal(std::string_view name);
std::vector<std::string_view> metal_names();

// The index whose normal-incidence reflectance is `f0` per channel and whose reflectance rises
// to 1 at grazing incidence, the behaviour of glTF's Schlick Fresnel for metals: Gulbrandsen,
// "Artist Friendly Metallic Fresnel", JCGT 3(4), 2014, with the edge tint g = 1, where his
// mapping reduces to eta = (1 - r) / (1 + r), k = 2 sqrt(r) / (1 + r).
ComplexIor complex_ior_from_reflectance(Rgb f0);

}  // namespace snee
