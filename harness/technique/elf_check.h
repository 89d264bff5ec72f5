#pragma once
// A plugin file's structure, checked before the dynamic loader sees it. glibc's loader trusts
// what an ELF file declares: a segment past the file's end raises SIGBUS when touched, and a
// dynamic table or a segment address moved elsewhere sends it reading and writing through
// wild pointers (a segmentation fault in whatever command loaded the plugin). What is checked
// is what a linker always writes: every table and segment inside the file, loadable segments
// in ascending order without overlap and with file and memory offsets congruent, the dynamic
// table inside the file part of a loadable segment, and the dynamic entries that are
// addresses pointing into one.
#include <string>

namespace rl {

// Throws ConfigError("plugin PATH: not a whole shared object (WHY)") when a 64-bit ELF file
// breaks one of the rules above; other files are left to the loader, which names them.
void check_elf_is_whole(const std::string& path);

}  // namespace rl
