# Read by ctest after the discovered suites (tests/CMakeLists.txt appends it to the directory's
# TEST_INCLUDE_FILES): the suites that take over 10 s under the sanitizers, labelled `slow`.
# `ctest -LE slow` is the quick part of the suite, what scripts/sanitize.sh runs under ASan and
# UBSan in CI; the Release suite runs them all.
foreach(name Report RunFolder Claims TruthExact AoMap QuadtreeSearch MultilayerScenes)
  set_tests_properties(${name} PROPERTIES LABELS slow)
endforeach()
