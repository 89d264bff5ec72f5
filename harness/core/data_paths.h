#pragma once
// Where ReliefLab's own files are at run time: the assets (the teapot, the real relief maps)
// and configs a sweep may name by a path relative to the repository root.
#include <string>

namespace rl {

// The folder holding assets/ and configs/: $RELIEFLAB_DATA_DIR when set; else, for a library
// installed under a prefix, <prefix>/share/relieflab (found from the library's own location);
// else, for the build tree's own libraries, the source tree they were built from. An installed
// or relocated library without its share/relieflab throws ConfigError saying so.
const std::string& data_root();

// Whether this library is the one the build made, in its build folder (not an installed or
// relocated copy).
bool in_build_tree();

// The folder the core library was loaded from (the build folder, or <prefix>/lib).
std::string library_dir();

// Whether `text` is well-formed UTF-8 (no stray continuation byte, overlong form, surrogate or
// code point past U+10FFFF).
bool is_utf8(const std::string& text);
// Throws ConfigError naming `what` when `path` is not UTF-8: the run records its paths in JSON
// (sweep.json, the store, the report), which holds only UTF-8, and must refuse such a path
// before measuring anything, not after.
void require_utf8_path(const std::string& path, const std::string& what);

}  // namespace rl
