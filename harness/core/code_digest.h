#pragma once
// What code a measurement came from. The build digests every folder of the project's sources (a
// harness layer, a technique's folder) and its own settings (compiler, flags, library versions:
// cmake/CodeDigests.cmake); a plugin's folder is digested by its shared object's bytes when it
// loads. A stored row, a precompute and a cached truth name the digests of the code that made
// them, so a rebuilt change re-makes exactly what it touches and nothing else.
#include <cstdint>
#include <initializer_list>
#include <map>
#include <source_location>
#include <string>

namespace rl {

// Generated at build time: folder relative to the source root ("harness/truth",
// "techniques/relief") -> 16 hex digits; and the build's settings, as text and digest.
const std::map<std::string, std::string>& source_digests();
const char* build_settings();
const char* build_settings_digest();

// One digest of the build's settings and `folders`' sources ("harness/metrics", ...); a folder
// the build does not know throws std::logic_error (a misspelt name must not digest as nothing).
std::string code_digest(std::initializer_list<const char*> folders);

// The folder holding `source_file` (a __FILE__ or a std::source_location's file name) as
// source_digests() names it ("techniques/relief"), or the file's own folder, absolute, where it
// is outside the tree this build was made from (a plugin's).
std::string source_folder(const std::string& source_file);

// The digest of the code in `folder` (as source_folder() names it): the build's digest for a
// folder of its own tree, the registered one for a plugin's; "" when neither knows it.
std::string folder_digest(const std::string& folder);
// A plugin's folder, digested by its shared object's bytes when it loaded (technique/plugins.h).
void register_folder_digest(const std::string& folder, const std::string& digest);

// The digest of the code a precompute made at `where` ran: the harness layers a precompute can
// call and the caller's own folder (a technique's, for its cone map or safety radii). The
// precompute and truth caches name it in every entry (core/precompute_cache.h).
std::string precompute_code_digest(const std::source_location& where);

// A file's bytes digested (16 hex digits), once per process for each (path, size, modification
// time): a sweep whose scenes share a map reads it once for its identity. "" when the file
// cannot be read.
std::string file_digest(const std::string& path);
// How many files file_digest() has read (not answered from its memo), for the tests and the
// hashing benchmark.
uint64_t file_digest_reads();

}  // namespace rl
