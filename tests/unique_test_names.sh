#!/usr/bin/env bash
# Every ctest name in the build tree BUILD names one test: prints the names given to more than
# one add_test (the build's CTestTestfile.cmake files and the test programs' group files they
# include) and fails if there are any. Reads the files rather than running `ctest -N`, which would rewrite
# Testing/Temporary/LastTest.log under the ctest run this is part of.
set -euo pipefail
build="$1"
# The group files read are those a CTestTestfile.cmake includes: a build folder can hold group
# files of programs that no longer exist.
mapfile -d '' testfiles < <(find "$build" -name CTestTestfile.cmake -print0)
mapfile -t groups < <(sed -nE 's/^include\("([^"]+_groups\.cmake)"\)$/\1/p' "${testfiles[@]}")
lines=$(cat "${testfiles[@]}" "${groups[@]}" | grep -h '^add_test' || true)
names=$(sed -nE 's/^add_test\(\[=\[([^]]+)\]=\].*/\1/p' <<<"$lines")
# A name this cannot read would hide its duplicates: every add_test must give one.
count() { grep -c . <<<"$1" || true; }
if [ -z "$lines" ]; then
  echo "no add_test under $build"
  exit 1
fi
if [ "$(count "$names")" -ne "$(count "$lines")" ]; then
  echo "could not read a test name from every add_test line:"
  grep -vE '^add_test\(\[=\[[^]]+\]=\]' <<<"$lines" || true
  exit 1
fi
duplicates=$(sort <<<"$names" | uniq -d)
if [ -n "$duplicates" ]; then
  echo "ctest names given to more than one test:"
  echo "$duplicates"
  exit 1
fi
echo "$(count "$names") ctest names, each once"
