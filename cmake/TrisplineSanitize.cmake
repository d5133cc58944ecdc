# Sanitizer and fuzzing builds (scripts/sanitize.sh makes one in build-asan/; docs/decisions.md "Sanitizers and
# fuzzing in CI").
#
#   TRISPLINE_SANITIZE  every target compiled and linked with AddressSanitizer + UndefinedBehaviorSanitizer; a
#                       finding aborts the process (no recovery), so a ctest run fails on it.
#   TRISPLINE_FUZZ      also instruments every target for libFuzzer's coverage (-fsanitize=fuzzer-no-link) and builds
#                       the fuzz targets of tests/fuzz/. Needs clang (Debian: clang-14, libclang-rt-14-dev).
option(TRISPLINE_SANITIZE "Build with AddressSanitizer + UndefinedBehaviorSanitizer" OFF)
option(TRISPLINE_FUZZ "Build the libFuzzer targets of tests/fuzz (clang; implies TRISPLINE_SANITIZE)" OFF)

if(TRISPLINE_FUZZ)
  set(TRISPLINE_SANITIZE ON)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TRISPLINE_FUZZ needs clang (libFuzzer); configure with -DCMAKE_CXX_COMPILER=clang++-14 "
                        "-DCMAKE_C_COMPILER=clang-14 (Debian packages clang-14, libclang-rt-14-dev)")
  endif()
endif()

if(TRISPLINE_SANITIZE)
  set(_trispline_san -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${_trispline_san})
  add_link_options(${_trispline_san})
  if(TRISPLINE_FUZZ)
    add_compile_options(-fsanitize=fuzzer-no-link)
  endif()
  set(TRISPLINE_SANITIZE_O2_MODULES spline ffd ddm ddm_auto_uv)  # trispline_module() compiles these at -O2
  message(STATUS "trispline: AddressSanitizer + UBSan on every target (libFuzzer coverage: ${TRISPLINE_FUZZ})")
endif()
