#include "technique/elf_check.h"

#include <elf.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/error.h"

namespace rl {
namespace {

// The file's bytes and what is read from them; `refuse` names the file.
struct ElfFile {
  std::string path, bytes;
  Elf64_Ehdr header{};
  std::vector<Elf64_Phdr> segments;

  [[noreturn]] void refuse(const std::string& why) const {
    throw ConfigError("plugin " + path + ": not a whole shared object (" + why + ")");
  }
  // [offset, offset + length) within the file, without the sum wrapping around.
  bool inside(uint64_t offset, uint64_t length) const {
    return offset <= bytes.size() && length <= bytes.size() - offset;
  }
};

void read_program_headers(ElfFile& f) {
  const Elf64_Ehdr& h = f.header;
  if (h.e_phentsize != sizeof(Elf64_Phdr) ||
      !f.inside(h.e_phoff, uint64_t(h.e_phnum) * sizeof(Elf64_Phdr)))
    f.refuse("its program headers lie past its end");
  if (h.e_shnum && !f.inside(h.e_shoff, uint64_t(h.e_shnum) * h.e_shentsize))
    f.refuse("its section headers lie past its end: cut short?");
  f.segments.resize(h.e_phnum);
  if (h.e_phnum > 0)  // an empty vector's data() may be null
    std::memcpy(f.segments.data(), f.bytes.data() + h.e_phoff, h.e_phnum * sizeof(Elf64_Phdr));
}

// Loadable segments: inside the file, no larger on file than in memory, congruent with their
// alignment (a power of two), in ascending order of address and of file offset without
// overlap (a segment mapped from another's bytes would run them as its code).
void check_load_segments(const ElfFile& f) {
  uint64_t end_of_last = 0, file_end_of_last = 0;  // in memory and in the file
  bool any = false;
  for (const Elf64_Phdr& p : f.segments) {
    if ((p.p_type == PT_LOAD || p.p_type == PT_DYNAMIC) && !f.inside(p.p_offset, p.p_filesz))
      f.refuse("a segment of " + std::to_string(p.p_filesz) + " bytes at " +
               std::to_string(p.p_offset) + " runs past its " + std::to_string(f.bytes.size()) +
               " bytes: cut short?");
    if (p.p_type != PT_LOAD) continue;
    const bool power_of_two = p.p_align != 0 && (p.p_align & (p.p_align - 1)) == 0;
    if (!power_of_two || p.p_offset % p.p_align != p.p_vaddr % p.p_align)
      f.refuse("a loadable segment's offset and address disagree with its alignment");
    if (p.p_filesz > p.p_memsz || p.p_vaddr > ~uint64_t(0) - p.p_memsz)
      f.refuse("a loadable segment's sizes are inconsistent");
    if (any && (p.p_vaddr < end_of_last || p.p_offset < file_end_of_last))
      f.refuse("its loadable segments overlap or are out of order");
    end_of_last = p.p_vaddr + p.p_memsz;
    file_end_of_last = p.p_offset + p.p_filesz;
    any = true;
  }
  if (!any) f.refuse("no loadable segment");
}

// The segments that describe parts of loaded memory (read-only after relocation, thread-local
// data, unwind tables, notes) lie inside a loadable segment's memory: the loader acts on them
// (mprotect, copies) as declared.
void check_described_segments(const ElfFile& f) {
  for (const Elf64_Phdr& d : f.segments) {
    if (d.p_type != PT_GNU_RELRO && d.p_type != PT_TLS && d.p_type != PT_GNU_EH_FRAME &&
        d.p_type != PT_NOTE && d.p_type != PT_INTERP)
      continue;
    // Of thread-local data the loader copies only the initialised image (a .tbss-only segment
    // may sit at an address no loadable segment covers, as lld lays it out).
    const uint64_t size = d.p_type == PT_TLS ? d.p_filesz : d.p_memsz;
    if (size == 0) continue;
    const bool within = std::any_of(f.segments.begin(), f.segments.end(), [&](const Elf64_Phdr& p) {
      return p.p_type == PT_LOAD && d.p_vaddr >= p.p_vaddr && d.p_vaddr - p.p_vaddr <= p.p_memsz &&
             size <= p.p_memsz - (d.p_vaddr - p.p_vaddr);
    });
    if (!within)
      f.refuse("a segment of type " + std::to_string(d.p_type) + " lies outside its loaded memory");
  }
}

// The loadable segment whose file-backed part holds [address, address + length), or null.
const Elf64_Phdr* file_backed(const ElfFile& f, uint64_t address, uint64_t length) {
  for (const Elf64_Phdr& p : f.segments)
    if (p.p_type == PT_LOAD && address >= p.p_vaddr && address - p.p_vaddr <= p.p_filesz &&
        length <= p.p_filesz - (address - p.p_vaddr))
      return &p;
  return nullptr;
}

// The dynamic table lies in the file part of a loadable segment, at the file offset its
// address implies, and its address entries point into the file part of one.
void check_dynamic(const ElfFile& f) {
  for (const Elf64_Phdr& d : f.segments) {
    if (d.p_type != PT_DYNAMIC) continue;
    const Elf64_Phdr* load = file_backed(f, d.p_vaddr, d.p_filesz);
    if (!load || d.p_offset - load->p_offset != d.p_vaddr - load->p_vaddr)
      f.refuse("its dynamic table lies outside its loaded data");
    const size_t count = d.p_filesz / sizeof(Elf64_Dyn);
    std::vector<Elf64_Dyn> entries(count);
    if (count > 0)  // an empty vector's data() may be null
      std::memcpy(entries.data(), f.bytes.data() + d.p_offset, count * sizeof(Elf64_Dyn));
    for (const Elf64_Dyn& e : entries) {
      if (e.d_tag == DT_NULL) break;
      switch (e.d_tag) {
        case DT_STRTAB:
        case DT_SYMTAB:
        case DT_RELA:
        case DT_JMPREL:
        case DT_INIT_ARRAY:
        case DT_FINI_ARRAY:
        case DT_HASH:
        case DT_GNU_HASH:
        case DT_VERSYM:
        case DT_VERNEED:
        case DT_VERDEF:
        case DT_PLTGOT:
        case DT_INIT:
        case DT_FINI:
          if (!file_backed(f, e.d_un.d_ptr, 1))
            f.refuse("a dynamic entry (tag " + std::to_string(e.d_tag) +
                     ") points outside its loaded data");
      }
    }
  }
}

}  // namespace

void check_elf_is_whole(const std::string& path) {
  ElfFile f;
  f.path = path;
  {
    std::ifstream in(path, std::ios::binary);
    f.bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  if (f.bytes.size() < sizeof(Elf64_Ehdr) || std::memcmp(f.bytes.data(), ELFMAG, SELFMAG) != 0)
    f.refuse("no ELF header");
  std::memcpy(&f.header, f.bytes.data(), sizeof f.header);
  if (f.header.e_ident[EI_CLASS] != ELFCLASS64) return;  // the loader's own check names it
  read_program_headers(f);
  check_load_segments(f);
  check_described_segments(f);
  check_dynamic(f);
}

}  // namespace rl
