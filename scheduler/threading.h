// Per-thread floating-point setup every worker that traces rays must do.
#pragma once

#include <pmmintrin.h>
#include <xmmintrin.h>

namespace snee {

// Embree asks for flush-to-zero and denormals-are-zero in every thread that traces rays.
inline void set_flush_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace snee
