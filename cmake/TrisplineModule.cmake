# trispline_module(<name> SOURCES <files...> DEPS <targets...>)
# Makes static library trispline_<name> with the project's warnings and the repository root on the include path,
# so every header is included as "core/spline/knot_vector.h", "gpu/render/renderer.h", ...
# Unity batches of 8 files: a module's files share one parse of the project's and libraries' headers (the build is
# CPU-bound on 2 cores, so fewer parses is less time: the editor's cold build 594 → 477 s, docs/performance.md).
# Files compiled with options of their own (the FFD kernels' instruction sets) are built alone; file-local helpers
# must have distinct names across a module, as in any unity build. The sanitizer build is batched the same way.
function(trispline_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(trispline_${name} STATIC ${ARG_SOURCES})
  set_target_properties(trispline_${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  target_include_directories(trispline_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_compile_options(trispline_${name} PRIVATE ${TRISPLINE_WARNINGS})
  target_compile_definitions(trispline_${name} PUBLIC GLM_FORCE_XYZW_ONLY GLM_ENABLE_EXPERIMENTAL)
  target_link_libraries(trispline_${name} PUBLIC glm::glm ${ARG_DEPS})
  set_target_properties(trispline_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  # The sanitizer build's -O1 leaves GLM's accessors and the small spline helpers as calls; the numeric modules the
  # core tests spend their time in (B-spline evaluation, FFD bounds and refinement, DDM) run ~2× faster at -O2, which
  # keeps every ASan and UBSan check.
  if(TRISPLINE_SANITIZE AND name IN_LIST TRISPLINE_SANITIZE_O2_MODULES)
    target_compile_options(trispline_${name} PRIVATE -O2)
  endif()
endfunction()

# trispline_test(<name> SOURCES <files...> DEPS <targets...> [LABELS <labels>])
# One GoogleTest executable; each of its suites is one ctest test (cmake/TrisplineGtestSuites.cmake, run after linking).
function(trispline_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  # Unity batches: a suite's files share one parse of GoogleTest and the project headers (about half the tests'
  # compile time on 2 cores). Helpers in different files of a suite must not share a name, as in any unity build.
  set_target_properties(${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  target_compile_options(${name} PRIVATE ${TRISPLINE_WARNINGS})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main GTest::gmock)
  target_compile_definitions(${name} PRIVATE TRISPLINE_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             TRISPLINE_BINARY_DIR="${PROJECT_BINARY_DIR}")
  string(REPLACE ";" "," labels "${ARG_LABELS}")
  set(ctest_file "${CMAKE_CURRENT_BINARY_DIR}/${name}_suites.cmake")
  add_custom_command(TARGET ${name} POST_BUILD
    COMMAND "${CMAKE_COMMAND}" "-DTEST_EXECUTABLE=$<TARGET_FILE:${name}>" "-DTEST_WORKING_DIR=${CMAKE_CURRENT_BINARY_DIR}"
            "-DTEST_LABELS=${labels}" "-DCTEST_FILE=${ctest_file}" -P "${PROJECT_SOURCE_DIR}/cmake/TrisplineGtestSuites.cmake"
    BYPRODUCTS "${ctest_file}"
    VERBATIM)
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${ctest_file}")
endfunction()
