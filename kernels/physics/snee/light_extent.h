// How large each light looks from the objects SNEE renders, as the half-angle of the cone of
// directions it fills (degrees): the quantity that decides whether SNEE pays. Its strategies
// exist for lights that unidirectional sampling through a refractive boundary rarely finds
// (docs/method.md 3.11); a light that fills a large part of the sky is found by the path
// tracer's own BSDF samples, and there SNEE's probes and connections only cost time.
#pragma once

#include "scene/scene.h"

namespace snee {

// The apparent size of a light that fills every direction, and the largest limit.
inline constexpr float kWholeSkyDegrees = 180.0f;

// 0 for delta lights (directional, point, spot); a cone's half-angle; 180 for constant and
// image environments. An area light's is the half-angle of the cone from the centre of the
// objects with a medium that holds the light's bounding sphere (180 from inside it).
float light_half_angle_degrees(const Scene& scene, const Light& light);

// The smallest over scene.lights, 180 when there is none.
float smallest_light_half_angle_degrees(const Scene& scene);

// The largest over the lights that escaped rays see (cone, constant, environment image): the
// only ones bottom-to-top can find, 0 when there is none.
float largest_escaped_light_half_angle_degrees(const Scene& scene);

}  // namespace snee
