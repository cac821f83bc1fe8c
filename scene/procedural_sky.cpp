#include "scene/procedural_sky.h"

#include <cmath>

namespace snee {

namespace {

Rgb lerp(Rgb a, Rgb b, float t) {
  return a * (1 - t) + b * t;
}

Rgb sky_radiance(Vec3 d) {
  const Rgb zenith(0.25f, 0.42f, 0.85f);
  const Rgb horizon(1.0f, 0.82f, 0.6f);
  const Rgb ground(0.06f, 0.05f, 0.04f);
  const Rgb sky = lerp(horizon, zenith, std::sqrt(std::max(d.y, 0.0f)));
  // A short blend below the horizon so the image has no hard edge to alias on.
  Rgb c = lerp(ground, sky, smoothstep(-0.08f, 0.0f, d.y));
  const Vec3 lobe_axis = normalize(Vec3(-0.5f, 0.7f, 0.5f));
  c += Rgb(3.0f, 2.8f, 2.4f) * std::exp(8.0f * (dot(d, lobe_axis) - 1.0f));
  return c;
}

}  // namespace

RgbImage make_soft_sky(int width, int height) {
  RgbImage image;
  image.width = width;
  image.height = height;
  image.source = "procedural soft sky";
  image.pixels.resize(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    // Inverse of RgbImage's mapping at the pixel centre: v = theta / pi, u = phi / (2 pi) + 0.5
    // with phi = atan2(d.x, -d.z).
    const float theta = kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    for (int x = 0; x < width; ++x) {
      const float phi =
          2 * kPi * ((static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 0.5f);
      const Vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                   -std::sin(theta) * std::cos(phi));
      image.pixels[static_cast<size_t>(y) * width + x] = sky_radiance(d);
    }
  }
  return image;
}

}  // namespace snee
