#include "scene/metals.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace snee {

namespace {

struct NamedMetal {
  std::string_view name;
  ComplexIor ior;
};

// Palik, "Handbook of Optical Constants of Solids" (1985), as tabulated spectrally with Mitsuba
// and pbrt-v3 and reduced to linear sRGB primaries by Tungsten (Bitterli,
// src/core/bsdfs/ComplexIorData.hpp). Normal-incidence reflectances: gold (0.97, 0.80, 0.32),
// silver (0.98, 0.96, 0.91), copper (0.95, 0.62, 0.51), aluminium (0.93, 0.92, 0.92).
constexpr std::array<NamedMetal, 4> kMetals{{
    {"gold",
     {{0.1431189557f, 0.3749570432f, 1.4424785571f},
      {3.9831604247f, 2.3857207478f, 1.6032152899f}}},
    {"silver",
     {{0.1552646489f, 0.1167232965f, 0.1383806959f},
      {4.8283433224f, 3.1222459278f, 2.1469504455f}}},
    {"copper",
     {{0.2004376970f, 0.9240334304f, 1.1022119527f},
      {3.9129485033f, 2.4528477015f, 2.1421879552f}}},
    {"aluminium",
     {{1.6574599595f, 0.8803689579f, 0.5212287346f},
      {9.2238691996f, 6.2695232477f, 4.8370012281f}}},
}};

}  // namespace

std::optional<ComplexIor> find_metal(std::string_view name) {
  const auto it = std::find_if(kMetals.begin(), kMetals.end(),
                               [&](const NamedMetal& m) { return m.name == name; });
  if (it == kMetals.end()) return std::nullopt;
  return it->ior;
}

std::vector<std::string_view> metal_names() {
  std::vector<std::string_view> names;
  for (const NamedMetal& m : kMetals) names.push_back(m.name);
  return names;
}

ComplexIor complex_ior_from_reflectance(Rgb f0) {
  ComplexIor ior;
  for (int c = 0; c < 3; ++c) {
    const float r = std::clamp(f0[c], 0.0f, 1.0f);
    ior.eta[c] = (1.0f - r) / (1.0f + r);
    ior.k[c] = 2.0f * std::sqrt(r) / (1.0f + r);
  }
  return ior;
}

}  // namespace snee
