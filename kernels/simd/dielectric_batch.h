// The dielectric samplers of kernels/physics/bsdf/dielectric.h for a batch of lanes, each with its
// own interface: the templates' FloatBatch forms, named in snee::simd for the batched kernels. One
// template, so bit for bit the scalar functions on every lane (tests/test_shading_batch.cpp).
#pragma once

#include "kernels/physics/bsdf/dielectric.h"
#include "kernels/simd/frame_batch.h"

namespace snee::simd {

using DielectricLanes = DielectricT<FloatBatch>;
using BsdfSampleBatch = BsdfSampleT<FloatBatch>;
using snee::dielectric_sample;
using snee::dielectric_sample_transmission;
using snee::ggx_d;

}  // namespace snee::simd
