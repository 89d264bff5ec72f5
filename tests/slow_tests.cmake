# Read by ctest after the discovered suites (tests/CMakeLists.txt appends it to the directory's
# TEST_INCLUDE_FILES): the suites that take over 10 s under the sanitizers, labelled `slow`.
# `ctest -LE slow` is the quick part of the suite, what scripts/sanitize.sh runs under ASan and
# UBSan in CI; the Release suite runs them all.
foreach(name Report RunFolder Claims TruthExact AoMap QuadtreeSearch MultilayerScenes)
  set_tests_properties(${name} PROPERTIES LABELS slow)
endforeach()
# Where no earlier run left timings (a fresh clone, as in CI), ctest starts tests in the order
# they were declared; the longest (over 10 s in Release or 15 s sanitized) start first instead,
# so that none is left running alone at the end.
foreach(name TruthExact RunFolder Report FuzzConfig FuzzPlugins NonSquare BadConfig Faults
        Compare Sweep SceneShadows RegistryHardCases Provenance)
  set_tests_properties(${name} PROPERTIES COST 50)
endforeach()
