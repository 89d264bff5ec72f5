# One CTest test per GoogleTest suite (per parameter, for value-parameterised suites), found
# after each build like gtest_discover_tests does it.
#
# Why not one process per test: every test program loads ~270 shared libraries (OpenImageIO's
# dependencies) and makes a GL context, ~0.3 s before the first test runs; with 339 tests that
# start-up was a third of the suite's time on 2 cores. A suite's tests share one process, and a
# failure still names its test in the output. Value-parameterised tests (the contract's
# "Clause/technique") are grouped by their parameter instead, so each technique's promise is one
# CTest test: `ctest -R contract.Registry.relief_exact`.
#
#   relieflab_discover_test_groups(<target> [PREFIX <p>] [LABELS <l>...] [TIMEOUT <s>])
set(RELIEFLAB_GROUP_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/group_gtests.cmake)

function(relieflab_discover_test_groups target)
  cmake_parse_arguments(arg "" "PREFIX;TIMEOUT" "LABELS" ${ARGN})
  if(NOT arg_TIMEOUT)
    set(arg_TIMEOUT 300)
  endif()
  set(include_file ${CMAKE_CURRENT_BINARY_DIR}/${target}_groups.cmake)
  add_custom_command(
    TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -D TEST_EXECUTABLE=$<TARGET_FILE:${target}>
            -D TEST_PREFIX=${arg_PREFIX} -D TEST_LABELS=${arg_LABELS}
            -D TEST_TIMEOUT=${arg_TIMEOUT} -D TEST_WORKING_DIR=${CMAKE_CURRENT_BINARY_DIR}
            -D OUTPUT_FILE=${include_file} -P ${RELIEFLAB_GROUP_SCRIPT}
    BYPRODUCTS ${include_file}
    VERBATIM)
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${include_file})
endfunction()
