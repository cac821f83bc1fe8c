# Warnings, determinism and tuning flags applied to every snee target through snee_flags.
# -ffp-contract=off keeps a*b+c from becoming an FMA in one build and not another: images must
# be bitwise identical across thread counts and batch sizes, and tests compare SIMD to scalar.
add_library(snee_flags INTERFACE)
target_compile_options(snee_flags INTERFACE -Wall -Wextra -Wpedantic -Wshadow
  -ffp-contract=off -fno-fast-math)
if(SNEE_WERROR)
  target_compile_options(snee_flags INTERFACE -Werror)
endif()
if(SNEE_NATIVE)
  target_compile_options(snee_flags INTERFACE -march=native)
  # GCC 12 flags the deliberately undefined merge operands of its own AVX-512 intrinsics as
  # uninitialised once they are inlined (GCC bug 105593), which -Werror turns into errors in
  # every xsimd kernel of an AVX-512 build.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(snee_flags INTERFACE -Wno-uninitialized -Wno-maybe-uninitialized)
  endif()
else()
  # Portable default: x86-64-v2 (SSE4.2) runs on every x86 machine of the last decade.
  target_compile_options(snee_flags INTERFACE -march=x86-64-v2)
endif()
target_include_directories(snee_flags INTERFACE ${PROJECT_SOURCE_DIR})
