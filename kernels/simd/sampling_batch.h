// The sampling templates of kernels/physics/sampling.h and core/math.h (sample_uniform_sphere,
// spherical_direction, safe_sqrt) named in snee::simd for the batched kernels. The azimuth
// goes through lanewise_sincos (lane_batch.h), so x and y agree with the scalar functions' within
// the bound of README.md (tests/test_shading_batch.cpp) and the polar part bit for bit.
#pragma once

#include "kernels/physics/sampling.h"
#include "kernels/simd/vec3_batch.h"

namespace snee::simd {

using snee::safe_sqrt;
using snee::sample_uniform_sphere;
using snee::spherical_direction;

}  // namespace snee::simd
