// A procedurally generated low-frequency lat-long environment for the built-in scenes: the
// "low-frequency environment map" illumination of the SNEE paper's test grid, without a file.
#pragma once

#include "scene/scene.h"

namespace snee {

// Blue sky fading to a warm horizon, dark ground, and a broad soft bright lobe (an overcast sun)
// high in the front-left; about 0.1 to 3 in radiance. Follows RgbImage's direction convention.
RgbImage make_soft_sky(int width, int height);

}  // namespace snee
