// hg_sample (kernels/physics/medium/henyey_greenstein.h) for a batch of lanes: the template's
// FloatBatch form, named in snee::simd for the batched kernels. Its azimuth comes from
// lanewise_sincos instead of libm, so directions agree with the scalar ones to a few units in the
// last place of 1 (bound in README.md, checked by tests/test_shading_batch.cpp) and the pdf, which
// does not depend on the azimuth, bit for bit.
#pragma once

#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/simd/frame_batch.h"
#include "kernels/simd/sampling_batch.h"

namespace snee::simd {

using HgSampleBatch = HgSample<FloatBatch>;
using snee::hg_sample;

}  // namespace snee::simd
