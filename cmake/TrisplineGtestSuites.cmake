# Registers one ctest test per GoogleTest suite of a test executable (run after the executable is linked; see
# trispline_test in TrisplineModule.cmake). Each suite runs in one process (`--gtest_filter=Suite.*`), so the ~0.4 s
# it takes the dynamic loader to map a test binary's ~260 shared libraries (OpenImageIO's dependencies) is paid once a
# suite instead of once a test. A failure names its test in the output (ctest --output-on-failure).
#
# Variables (cmake -D ... -P TrisplineGtestSuites.cmake):
#   TEST_EXECUTABLE   the GoogleTest executable
#   TEST_WORKING_DIR  the tests' working directory
#   TEST_LABELS       ctest labels, comma-separated
#   CTEST_FILE        the file written (included by the directory's CTestTestfile.cmake)
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
                WORKING_DIRECTORY "${TEST_WORKING_DIR}"
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE status TIMEOUT 60)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "Listing the tests of ${TEST_EXECUTABLE} failed (${status}):\n${listing}\n${errors}")
endif()

# Suite lines start in column 0 and end with '.' (a typed or parameterised suite adds "  # TypeParam = …"); test lines
# are indented. Characters CMake lists treat specially never occur in suite names, so they are blanked first.
string(REGEX REPLACE "[][;\\\\]" "_" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(suites "")
foreach(line IN LISTS lines)
  if(line MATCHES "^([A-Za-z0-9_/]+)\\.( .*)?$")
    list(APPEND suites "${CMAKE_MATCH_1}")
  endif()
endforeach()
list(REMOVE_DUPLICATES suites)
if(NOT suites)
  message(FATAL_ERROR "${TEST_EXECUTABLE} lists no test suite:\n${listing}")
endif()

string(REPLACE "," ";" labels "${TEST_LABELS}")
set(script "")
foreach(suite IN LISTS suites)
  string(APPEND script "add_test([==[${suite}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${suite}.*]==])\n"
                       "set_tests_properties([==[${suite}]==] PROPERTIES WORKING_DIRECTORY [==[${TEST_WORKING_DIR}]==]"
                       " LABELS [==[${labels}]==]"
                       # A skipped test fails its suite: nothing in CI skips itself quietly.
                       " FAIL_REGULAR_EXPRESSION [==[\\[  SKIPPED \\]]==])\n")
endforeach()
file(WRITE "${CTEST_FILE}" "${script}")
