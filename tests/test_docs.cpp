// Documentation that cannot drift: the README's technique table and every technique README's
// interface table are generated from the registry (technique/technique_docs.h). These tests
// fail when a committed block differs from what describe() says now; the fix is
// `relieflab docs --update`. They iterate the registry, so a new plugin without a README (or
// with a stale one) fails the day it lands.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "config/config.h"
#include "technique/technique.h"
#include "technique/technique_docs.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

const fs::path kRepo = fs::path(RELIEFLAB_TEST_DIR).parent_path();

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The file with its block `key` regenerated equals the file: the block is current.
void expect_block_current(const fs::path& file, const std::string& key) {
  ASSERT_TRUE(fs::exists(file)) << file << " is missing";
  const std::string text = read_text(file);
  const auto keys = generated_block_keys(text);
  ASSERT_EQ(std::count(keys.begin(), keys.end(), key), 1)
      << file << " must hold one generated block '" << key << "'";
  const auto blocks = generated_blocks();
  EXPECT_EQ(update_generated_blocks(text, {{key, blocks.at(key)}}), text)
      << file << ": block '" << key << "' is stale; run `relieflab docs --update`";
}

TEST(Docs, ReadmeTechniqueTableMatchesTheRegistry) {
  expect_block_current(kRepo / "README.md", "techniques");
}

// Every declared column (core/columns.h), with its unit and meaning, as the producers declare it.
TEST(Docs, ReadmeColumnReferenceMatchesTheDeclarations) {
  expect_block_current(kRepo / "docs" / "columns.md", "columns");
  const std::string table = columns_markdown();
  for (const char* name : {"wrong_pct", "warp_fetches_per_px", "truth_bound_texels", "frame_ms",
                           "layer_overflow_pct", "cell_grid", "odd_missed_rays"})
    EXPECT_NE(table.find(std::string("| `") + name + "` |"), std::string::npos) << name;
}

TEST(Docs, EveryTechniqueHasAReadmeWithItsCurrentInterface) {
  const auto names = TechniqueRegistry::instance().names();
  ASSERT_FALSE(names.empty());
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    expect_block_current(kRepo / "techniques" / name / "README.md", "interface of " + name);
  }
}

// A user of the repository has no ../shared/ folder: a README cites the paper itself.
TEST(Docs, TechniqueReadmesCiteNoPathOutsideTheRepository) {
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    const fs::path readme = kRepo / "techniques" / name / "README.md";
    if (!fs::exists(readme)) continue;  // a plugin's README lives with it
    std::ifstream in(readme);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text.find("../shared"), std::string::npos) << readme;
  }
}

TEST(Docs, TechniqueTableListsEveryTechniqueAndItsParameters) {
  const std::string table = techniques_markdown();
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    EXPECT_NE(table.find("[`" + name + "`]"), std::string::npos) << name;
    const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
    const std::string iface = interface_markdown(info);
    for (const ParamSpec& p : info.params)
      EXPECT_NE(iface.find("| `" + p.name + "` |"), std::string::npos) << name << "." << p.name;
  }
}

TEST(Docs, UpdateReplacesOnlyKnownBlocksAndKeepsTheRest) {
  const std::string open = "<!-- generated: a (relieflab docs --update) -->\n";
  const std::string open_b = "<!-- generated: b (relieflab docs --update) -->\n";
  const std::string close = "<!-- end generated -->";
  const std::string text =
      "intro\n" + open + "old a\n" + close + "\nmiddle\n" + open_b + "old b\n" + close + "\nend\n";
  EXPECT_EQ(
      update_generated_blocks(text, {{"a", "new a\n"}}),
      "intro\n" + open + "new a\n" + close + "\nmiddle\n" + open_b + "old b\n" + close + "\nend\n");
  EXPECT_EQ(generated_block_keys(text), (std::vector<std::string>{"a", "b"}));
  EXPECT_THROW(update_generated_blocks("x\n" + open + "never closed\n", {{"a", "y"}}),
               std::runtime_error);
}

// `docs --update` with a plugin loaded wrote the plugin into the project's README (its table
// row, its columns, an interface block): the project's files describe its own techniques.
TEST(Docs, APluginLoadedIsLeftOutOfTheProjectsBlocks) {
  TechniqueRegistry& registry = TechniqueRegistry::instance();
  TechniqueEntry e = *registry.find("relief");
  e.info.name = "test_loaded_plugin";
  e.info.title = "Test plugin | with a bar";
  e.info.columns = {{.name = "test_plugin_column", .unit = "", .meaning = "a plugin's own"}};
  registry.add(e);
  registry.set_plugin("test_loaded_plugin", "/tmp/libtest_loaded_plugin.so");
  const auto all = generated_blocks(DocsScope::Registered);
  const auto own = generated_blocks(DocsScope::BuiltIn);
  registry.remove("test_loaded_plugin");
  EXPECT_NE(all.at("techniques").find("Test plugin \\| with a bar"), std::string::npos);
  EXPECT_NE(all.at("columns").find("`test_plugin_column`"), std::string::npos);
  EXPECT_TRUE(all.count("interface of test_loaded_plugin"));
  EXPECT_EQ(own.at("techniques").find("test_loaded_plugin"), std::string::npos);
  EXPECT_EQ(own.at("columns").find("test_plugin_column"), std::string::npos);
  EXPECT_FALSE(own.count("interface of test_loaded_plugin"));
  EXPECT_EQ(own.at("techniques"), techniques_markdown());  // the built-in ones, all of them
}

// The repository speaks to its readers: a step of its own history (a numbered stop or issue, a
// working period) means nothing to them; a date, a commit or the goal in words does. Every
// text file of the source tree (build and output folders aside) is held to it.
TEST(Docs, NoFileNamesAStepOfTheProjectsOwnHistory) {
  // Spelled in pieces, so that this file does not match itself; a word, then what follows it.
  const std::vector<std::pair<std::string, std::string>> words = {
      {std::string("st") + "op ", "0123456789"},
      {std::string("iss") + "ue ", "0123456789#"},
      {std::string("ses") + "sion", ""}};
  std::vector<std::string> found;
  for (auto it = fs::recursive_directory_iterator(kRepo); it != fs::recursive_directory_iterator();
       ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.rfind("build", 0) == 0 || name == "out" || name == ".git" ||
                               name == ".gl" || name == ".whl")) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || it->file_size() > (8u << 20)) continue;
    std::string text = read_text(it->path());
    if (text.find('\0') != std::string::npos) continue;  // a binary file
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const auto& [word, next] : words)
      for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
        if (next.empty() || (at + word.size() < text.size() &&
                             next.find(text[at + word.size()]) != std::string::npos)) {
          found.push_back(fs::relative(it->path(), kRepo).string() + ": '" +
                          text.substr(at, word.size() + 1) + "'");
          break;
        }
  }
  std::string list;
  for (const std::string& f : found) list += "\n  " + f;
  EXPECT_TRUE(found.empty()) << found.size() << " file(s):" << list;
}

// The front page's example is a committed config, shown as it is (its comment aside), and it
// parses with every file it names.
TEST(Docs, TheFrontPagesExampleIsTheCommittedConfig) {
  const std::string readme = read_text(kRepo / "README.md");
  std::string config = read_text(kRepo / "configs" / "first.toml");
  config = config.substr(config.find("[sweep]"));  // its header comment is not shown
  EXPECT_NE(readme.find("```toml\n" + config + "```"), std::string::npos)
      << "README.md does not show configs/first.toml as it is";
  EXPECT_NO_THROW(load_sweep_config((kRepo / "configs" / "first.toml").string()));
  // A front page a newcomer reads through; the manual is docs/.
  EXPECT_LE(std::count(readme.begin(), readme.end(), '\n'), 200) << "README.md grew past 200 lines";
}

// The results tree keeps one copy of the reports' style and scripts (results/report_assets/),
// which every committed report loads; a copy per folder was 46 identical d3 files and 59
// identical page scripts.
TEST(Docs, CommittedReportsShareOneCopyOfTheirStyleAndScripts) {
  std::map<std::string, int> copies;
  int reports = 0;
  for (const auto& e : fs::recursive_directory_iterator(kRepo / "results")) {
    for (const char* asset : {"d3.min.js", "report.js", "report.css"})
      copies[asset] += e.path().filename() == asset;
    if (e.path().filename() != "report.html") continue;
    ++reports;
    const std::string page = read_text(e.path());
    for (const char* tag : {"<script src=\"../report_assets/d3.min.js\">",
                            "<script src=\"../report_assets/report.js\">",
                            "<link rel=\"stylesheet\" href=\"../report_assets/report.css\">"})
      EXPECT_NE(page.find(tag), std::string::npos) << e.path() << " lacks " << tag;
    EXPECT_EQ(page.find("<style>"), std::string::npos) << e.path() << " embeds its style";
    EXPECT_EQ(page.find("<script>"), std::string::npos) << e.path() << " embeds its script";
  }
  EXPECT_GT(reports, 40);
  for (const auto& [asset, n] : copies) {
    EXPECT_EQ(n, 1) << asset;
    EXPECT_TRUE(fs::exists(kRepo / "results" / "report_assets" / asset)) << asset;
  }
}

}  // namespace
}  // namespace rl
