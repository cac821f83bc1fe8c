// The spectral-MIS free-flight templates of kernels/physics/medium/free_flight.h, named in
// snee::simd for the batched kernels. Their FloatBatch forms run the scalar arithmetic in the same
// order, but exp and log1p are xsimd's polynomials instead of libm's, so the results agree with the
// scalar functions only to a few ulp (bounds in README.md, checked by
// tests/test_free_flight_batch.cpp); for results below FLT_MIN xsimd's exp flushes to zero.
#pragma once

#include "kernels/physics/medium/free_flight.h"
#include "kernels/simd/vec3_batch.h"

namespace snee::simd {

using snee::channel_transmittance;
using snee::free_flight_channel_pdfs;
using snee::free_flight_pdf;
using snee::free_flight_sample;
using snee::free_flight_survival;
using snee::transmittance;

}  // namespace snee::simd
