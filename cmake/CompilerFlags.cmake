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
else()
  # Portable default: x86-64-v2 (SSE4.2) runs on every x86 machine of the last decade.
  target_compile_options(snee_flags INTERFACE -march=x86-64-v2)
endif()
target_include_directories(snee_flags INTERFACE ${PROJECT_SOURCE_DIR})
