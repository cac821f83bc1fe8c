// From linear radiance to a display value in [0, 1]: exposure, then a tone curve, then the sRGB
// transfer function. Pure functions over one channel; the preview writers (film_io.cpp) apply
// them per channel. docs/output-images.md gives the formulas and why they were chosen.
#pragma once

#include <cmath>

namespace snee {

enum class ToneCurve {
  kClamp,   // values above 1 clip to white: faithful below 1, loses every highlight
  kFilmic,  // Narkowicz's fit of the ACES filmic curve: a toe, and a shoulder that rolls off to 1
};

// Narkowicz (2015), "ACES Filmic Tone Mapping Curve": x (2.51 x + 0.03) / (x (2.43 x + 0.59) +
// 0.14), clipped to [0, 1]. Monotone on x >= 0 and 0 at 0; it reaches 1 near x = 7.24, so
// highlights up to about seven times the exposure still show gradation.
inline float aces_fitted(float x) {
  if (!(x > 0.0f)) return 0.0f;  // NaN and negatives show as black
  if (!(x < 7.3f)) return 1.0f;  // past the crossing of 1 (and inf)
  const float y = x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
  return y < 1.0f ? y : 1.0f;
}

// The sRGB opto-electronic transfer function (IEC 61966-2-1) on [0, 1], input clipped to it: a
// linear segment below 0.0031308, a 1/2.4 power with offset above. Not gamma 2.2, which differs
// most in the shadows.
inline float srgb_encode(float linear) {
  if (!(linear > 0.0f)) return 0.0f;
  if (linear >= 1.0f) return 1.0f;
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

struct ToneMap {
  float exposure_ev = 0.0f;  // each +1 doubles the radiance before the curve
  ToneCurve curve = ToneCurve::kClamp;

  // The display-referred, sRGB-encoded value in [0, 1] of one linear channel.
  float encode(float linear) const {
    const float exposed = linear * std::exp2(exposure_ev);
    return srgb_encode(curve == ToneCurve::kFilmic ? aces_fitted(exposed) : exposed);
  }
};

}  // namespace snee
