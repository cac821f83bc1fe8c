# Warnings, determinism and tuning flags applied to every snee target through snee_flags.
# -ffp-contract=off keeps a*b+c from becoming an FMA in one build and not another: images must
# be bitwise identical across thread counts and batch sizes, and tests compare SIMD to scalar.
add_library(snee_flags INTERFACE)
target_compile_options(snee_flags INTERFACE -Wall -Wextra -Wpedantic -Wshadow
  -ffp-contract=off -fno-fast-math)
if(SNEE_WERROR)
  target_compile_options(snee_flags INTERFACE -Werror)
endif()
# The instruction set: the portable x86-64-v2 (SSE4.2, runs on every x86 machine of the last
# decade) or the build machine's (SNEE_NATIVE), unless a target sets SNEE_MARCH: the SIMD
# modules (scheduler/CMakeLists.txt) build the same sources for x86-64-v3 (AVX2) and -v4
# (AVX-512).
if(SNEE_NATIVE)
  set(SNEE_BASELINE_MARCH native)
else()
  set(SNEE_BASELINE_MARCH x86-64-v2)
endif()
set(march "$<TARGET_PROPERTY:SNEE_MARCH>")
target_compile_options(snee_flags INTERFACE
  "-march=$<IF:$<BOOL:${march}>,${march},${SNEE_BASELINE_MARCH}>")
# GCC 12 flags the deliberately undefined merge operands of its own AVX-512 intrinsics as
# uninitialised once they are inlined (GCC bug 105593), which -Werror turns into errors in
# every xsimd kernel built for AVX-512.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  set(avx512 "$<OR:$<STREQUAL:${march},x86-64-v4>,$<AND:$<NOT:$<BOOL:${march}>>,$<BOOL:${SNEE_NATIVE}>>>")
  target_compile_options(snee_flags INTERFACE
    "$<${avx512}:-Wno-uninitialized;-Wno-maybe-uninitialized>")
endif()
target_include_directories(snee_flags INTERFACE ${PROJECT_SOURCE_DIR})
