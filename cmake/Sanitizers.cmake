# Sanitizer and fuzzing builds, each in a build directory of its own (scripts/sanitize.sh,
# scripts/fuzz.sh). Every target is instrumented, so a report can come from any layer; the
# Debian libraries (TBB, Embree, OpenImageIO, tinyobjloader) are not, which is why
# tests/sanitizer/ holds suppressions for what they do.
#
# SNEE_SANITIZE: a -fsanitize list such as "address,undefined". Undefined behaviour aborts
# (-fno-sanitize-recover) so that ctest sees it as a failure rather than a line in a log.
# SNEE_FUZZ: clang only; builds the scene layer and tests/fuzz/ alone, the library with
# -fsanitize=fuzzer-no-link (coverage feedback without libFuzzer's main) plus ASan and UBSan.
if(SNEE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SNEE_FUZZ needs clang (libFuzzer): configure with CXX=clang++")
  endif()
  if(NOT SNEE_SANITIZE)
    set(SNEE_SANITIZE "address,undefined")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(SNEE_SANITIZE)
  # Frame pointers and line tables (-g1: full debug info would double the build) make the
  # reports' stacks readable; they change no result.
  add_compile_options(-fsanitize=${SNEE_SANITIZE} -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer -g1)
  add_link_options(-fsanitize=${SNEE_SANITIZE})
endif()

# Code that runs once per command or test, never per ray or sample (the command line, the test
# bodies of the scene and CLI layers), compiles at -O0 in a sanitized build: instrumented alike,
# about 40% less compile time (test_cli.cpp: 37 s at -O1, 21 s at -O0), and no test waits on its
# speed. The render's code keeps the build's -O1.
function(snee_unoptimized_when_sanitized target)
  if(SNEE_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()
