#pragma once
// Documentation generated from the registry, so the README's technique table and each
// technique README's parameter table cannot drift from describe(). A Markdown file carries a
// generated block between
//   <!-- generated: KEY (relieflab docs --update) -->   and   <!-- end generated -->
// with KEY "techniques" (README.md), "columns" (docs/columns.md), or "interface of NAME"
// (techniques/NAME/README.md).
// `relieflab list --markdown` prints the blocks; `relieflab docs --update` rewrites them in
// place; tests/test_docs.cpp fails when a committed block differs.
#include <map>
#include <string>

#include "technique/technique.h"

namespace rl {

// Which techniques the blocks describe: all registered, or the project's own (a plugin loaded
// from RELIEFLAB_PLUGIN_PATH is not the project's, and must not be written into its README).
enum class DocsScope { Registered, BuiltIn };

// | technique | what | source | effects | proxies |, one row per technique in `scope`.
std::string techniques_markdown(DocsScope scope = DocsScope::Registered);
// | column | unit | kind | meaning | declared by |, every declared column (core/columns.h) but
// those of techniques outside `scope`.
std::string columns_markdown(DocsScope scope = DocsScope::Registered);
// Its effects and proxies, then | parameter | kind | default | range | meaning | (or "none").
std::string interface_markdown(const TechniqueInfo& info);

// Every generated block's key and content for the techniques in `scope`.
std::map<std::string, std::string> generated_blocks(DocsScope scope = DocsScope::Registered);

// `text` with the content of each generated block whose key is in `blocks` replaced; blocks
// of unknown keys are left as they are. Throws std::runtime_error on an unterminated block.
std::string update_generated_blocks(const std::string& text,
                                    const std::map<std::string, std::string>& blocks);

// The keys of the generated blocks `text` holds, in order.
std::vector<std::string> generated_block_keys(const std::string& text);

}  // namespace rl
