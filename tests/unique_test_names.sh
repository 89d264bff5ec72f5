#!/usr/bin/env bash
# Every ctest name in the build tree BUILD names one test: prints the names given to more than
# one add_test (the build's CTestTestfile.cmake files and the test programs' group files) and
# fails if there are any. Reads the files rather than running `ctest -N`, which would rewrite
# Testing/Temporary/LastTest.log under the ctest run this is part of.
set -euo pipefail
build="$1"
duplicates=$(find "$build" \( -name CTestTestfile.cmake -o -name '*_groups.cmake' \) -print0 |
  xargs -0 grep -h '^add_test' | sed -nE 's/^add_test\(\[=\[([^]]+)\]=\].*/\1/p' | sort | uniq -d)
if [ -n "$duplicates" ]; then
  echo "ctest names given to more than one test:"
  echo "$duplicates"
  exit 1
fi
count=$(find "$build" \( -name CTestTestfile.cmake -o -name '*_groups.cmake' \) -print0 |
  xargs -0 grep -h '^add_test' | wc -l)
echo "$count ctest names, each once"
[ "$count" -gt 0 ]
