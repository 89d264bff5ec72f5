// relieflab: run config-driven sweeps of relief-mapping techniques against Embree truth.
//   relieflab run [CONFIG] [--out DIR] [--shard I/N]
//                                        run a sweep (the built-in default without CONFIG),
//                                        or one deterministic slice of it (run/shard.h)
//   relieflab merge OUT SHARD_DIRS...    merge shards' results and write the tables
//   relieflab status DIR...              how far a run (or a sweep's shards) has got
//   relieflab report DIR                 rewrite a run's tables and report from its store
//   relieflab list [--markdown]          techniques with citation, effects and parameters
//   relieflab docs --update [--root DIR] rewrite the generated tables in README.md, docs/*.md and
//                                        techniques/*/README.md (technique/technique_docs.h)
//   relieflab compare BASE NEW [--tolerances FILE] [--allow-missing]
//                                        cells that got worse from one run to another; exit
//                                        status 1 when any did, or when the new run lacks
//                                        cells of the base (output/compare.h)
//   relieflab contract [--technique NAME]... [--all] [--plugins DIR]
//                                        hold techniques to the promise their describe()
//                                        declares (the contract suite, tests/contract/)
// Every command first loads the techniques built outside the tree from --plugins PATH and
// $RELIEFLAB_PLUGIN_PATH (technique/plugins.h).
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "claims/claims.h"
#include "claims/ledger.h"
#include "config/config.h"
#include "core/atomic_write.h"
#include "core/data_paths.h"
#include "core/error.h"
#include "output/compare.h"
#include "relief/pattern_mesh.h"
#include "relief/procedural.h"
#include "run/runner.h"
#include "run/shard.h"
#include "technique/plugins.h"
#include "technique/technique.h"
#include "technique/technique_docs.h"

namespace {

void print_list() {
  const auto& registry = rl::TechniqueRegistry::instance();
  for (const std::string& name : registry.names()) {
    const rl::TechniqueInfo& info = registry.find(name)->info;
    std::printf("%s — %s\n  citation: %s\n  effects:  %s\n", info.name.c_str(), info.title.c_str(),
                info.citation.c_str(), rl::join_effects(info.effects).c_str());
    if (const std::string& plugin = registry.find(name)->plugin; !plugin.empty())
      std::printf("  plugin:   %s\n", plugin.c_str());
    std::printf("  reads:    %s\n  draws on: %s\n", rl::reads_in_words(info.draws).c_str(),
                rl::draws_on_in_words(info.draws).c_str());
    if (info.params.empty()) std::printf("  parameters: none\n");
    for (const rl::ParamSpec& p : info.params) {
      std::printf("  %-16s %-5s default %s", p.name.c_str(), rl::param_kind_name(p.kind).c_str(),
                  rl::format_param(p, p.default_value).c_str());
      if (p.kind != rl::ParamKind::Bool)
        std::printf(", range [%s, %s]", rl::format_param(p, p.min_value).c_str(),
                    rl::format_param(p, p.max_value).c_str());
      std::printf("\n      %s\n", p.doc.c_str());
    }
    std::printf("\n");
  }
  std::printf("procedural reliefs:\n");
  for (const auto& k : rl::procedural_kinds()) {
    std::printf("  %-9s %s\n", k.name.c_str(), k.doc.c_str());
    for (const auto& o : k.options)
      std::printf("            %s = %g: %s (%g to %g)\n", o.name.c_str(), o.default_value,
                  o.doc.c_str(), o.min_value, o.max_value);
  }
  std::printf("non-height-field patterns (closed meshes baked into 'layers', default 4):\n");
  for (const std::string& kind : rl::pattern_mesh_kinds()) {
    std::printf("  %-9s options:", kind.c_str());
    for (const auto& [name, value] : rl::pattern_mesh_defaults(kind))
      std::printf(" %s = %g", name.c_str(), value);
    std::printf("\n");
  }
}

void print_markdown() {
  for (const auto& [key, text] : rl::generated_blocks())
    std::printf("<!-- %s -->\n%s\n", key.c_str(), text.c_str());
}

// Rewrites the generated blocks of README.md and every techniques/*/README.md under `root`;
// returns how many files changed.
int update_docs(const std::string& root) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files = {fs::path(root) / "README.md"};
  for (const auto& e : fs::directory_iterator(fs::path(root) / "docs"))
    if (e.path().extension() == ".md") files.push_back(e.path());
  for (const auto& e : fs::directory_iterator(fs::path(root) / "techniques"))
    if (fs::exists(e.path() / "README.md")) files.push_back(e.path() / "README.md");
  // The project's files describe its own techniques, whatever plugins this process loaded.
  const auto blocks = rl::generated_blocks(rl::DocsScope::BuiltIn);
  int changed = 0;
  for (const fs::path& f : files) {
    const std::string text = rl::read_text(f.string());
    const std::string updated = rl::update_generated_blocks(text, blocks);
    if (updated == text) continue;
    rl::write_text_atomic(f.string(), updated);
    std::printf("updated %s\n", f.string().c_str());
    ++changed;
  }
  return changed;
}

// `relieflab verify`: each folder's claims against its rows, README and report (a folder
// without claims.toml is listed as unchecked). Exit status 1 when any claim fails, or when no
// folder holds claims.
int verify_folders(const std::vector<std::string>& dirs, bool write) {
  int failures = 0, checked = 0;
  std::string report;
  for (const std::string& dir : dirs) {
    if (!std::filesystem::is_directory(dir))
      throw rl::ConfigError("verify: " + dir + ": no such folder");
    if (!std::filesystem::exists(dir + "/claims.toml")) {
      std::printf("%s: no claims.toml: its verdicts are not checked\n", dir.c_str());
      continue;
    }
    failures += rl::verify_result_folder(dir, write, report);
    ++checked;
  }
  std::fputs(report.c_str(), stdout);
  std::printf("relieflab: %d folder(s) with claims checked, %d failure(s)\n", checked, failures);
  // A check that checked nothing (a folder without claims, a mistyped glob) must not pass.
  if (checked == 0) {
    std::printf("relieflab: no folder given holds claims.toml: nothing was verified\n");
    return 1;
  }
  return failures ? 1 : 0;
}

// A config kept in the output folder under a name the run writes (rows.csv, a table, a file in
// plots/) would be overwritten by the run it configures: refused before anything is written.
void refuse_config_the_run_writes(const rl::SweepConfig& config, const std::string& config_path,
                                  const std::string& out_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path config_file = fs::weakly_canonical(config_path, ec);
  const fs::path out = fs::weakly_canonical(out_dir, ec);
  if (ec) return;
  const fs::path inside = config_file.lexically_relative(out);
  if (inside.empty() || *inside.begin() == "..") return;
  std::vector<std::string> written = rl::run_owned_names();
  for (const rl::TableSpec& t : config.tables) written.push_back(t.file);
  const std::string first = inside.begin()->string();
  if (std::find(written.begin(), written.end(), first) != written.end())
    throw rl::ConfigError("config " + config_path + " lies in the output folder " + out_dir +
                          " where the run writes '" + first +
                          "': it would be overwritten (move it, or choose another --out)");
}

// `relieflab run [CONFIG] [--out DIR] [--shard I/N]`; `shard_text` is null without --shard
// (an empty --shard "" is a mistake, not "every cell").
void run_sweep_command(const std::string& config_path, const std::string& out_dir, bool quiet,
                       const std::string* shard_text) {
  rl::SweepConfig config =
      config_path.empty() ? rl::default_sweep_config() : rl::load_sweep_config(config_path);
  rl::RunOptions options;
  options.out_dir = out_dir.empty() ? "out/" + config.name : out_dir;
  if (!config_path.empty()) refuse_config_the_run_writes(config, config_path, options.out_dir);
  options.progress = !quiet;
  if (shard_text) {
    options.shard = rl::parse_shard(*shard_text);
    // Shards run at once must not share a store: one folder each unless told otherwise.
    if (out_dir.empty() && options.shard.active())
      options.out_dir += "-shard-" + std::to_string(options.shard.index) + "-of-" +
                         std::to_string(options.shard.count);
  }
  rl::run_sweep(config, options);
}

// Every command's arguments, filled in by CLI11.
struct CliArgs {
  std::vector<std::string> plugin_paths;
  std::string config_path, out_dir, shard_text;
  CLI::Option* shard_option = nullptr;
  bool quiet = false;
  std::string merge_out;
  std::vector<std::string> merge_shards;
  bool markdown = false;
  std::string docs_root = ".";
  bool docs_update = false;
  std::vector<std::string> status_dirs;
  std::string report_dir;
  std::string base_dir, new_dir, tolerance_file;
  bool allow_missing = false;
  std::vector<std::string> verify_dirs;
  bool verify_write = false;
  std::string ledger_results = "results", ledger_readme = "README.md";
  bool ledger_write = false;
  std::vector<std::string> contract_techniques;
  bool contract_all = false;
};

// The commands and their options, bound to `a`.
void add_commands(CLI::App& app, CliArgs& a) {
  app.require_subcommand(1);
  app.fallthrough();  // --plugins may follow the command: `relieflab list --plugins DIR`
  app.add_option("--plugins", a.plugin_paths,
                 "Load techniques built outside the tree: a shared object, or a folder of them "
                 "(repeatable; also $RELIEFLAB_PLUGIN_PATH, ':'-separated)");

  CLI::App* run =
      app.add_subcommand("run", "Run a sweep (the built-in default sweep without CONFIG)");
  run->add_option("config", a.config_path, "Sweep config (TOML), e.g. configs/default.toml");
  run->add_option("-o,--out", a.out_dir,
                  "Output folder (default: out/<sweep name>); re-running into it resumes");
  run->add_flag("-q,--quiet", a.quiet, "No per-cell progress lines");
  a.shard_option =
      run->add_option("--shard", a.shard_text,
                      "Run only shard I of N (0-based), e.g. 2/8: cells sharing a truth trace stay "
                      "together, shards balanced by estimated cost; merge them with 'merge'");
  CLI::App* merge = app.add_subcommand(
      "merge", "Merge the results of a sweep's shards into OUT and write its tables");
  merge->add_option("out", a.merge_out, "Output folder of the merged sweep")->required();
  merge->add_option("shards", a.merge_shards, "The shards' output folders")->required();

  CLI::App* list = app.add_subcommand(
      "list", "List techniques (citation, effects, parameters) and procedural reliefs");
  list->add_flag("--markdown", a.markdown,
                 "The generated Markdown tables (README technique table, parameter tables)");
  CLI::App* docs = app.add_subcommand(
      "docs", "Rewrite the generated tables in README.md and techniques/*/README.md");
  docs->add_flag("--update", a.docs_update, "Rewrite the files (required)")->required();
  docs->add_option("--root", a.docs_root, "Repository root (default: the current folder)");

  CLI::App* status = app.add_subcommand(
      "status",
      "How far a run, or the shards of one sweep, has got: cells and truth traces "
      "done, per technique");
  status->add_option("dirs", a.status_dirs, "Output folder(s): one run or shard, or every shard")
      ->required();
  CLI::App* report = app.add_subcommand(
      "report",
      "Rewrite a run folder's rows.csv, tables, Pareto fronts and HTML report from "
      "its store (a run writes them itself)");
  report->add_option("dir", a.report_dir, "The run's output folder")->required();
  CLI::App* compare = app.add_subcommand(
      "compare",
      "Compare two runs' results cell by cell; exit status 1 when any cell got worse beyond "
      "tolerance, when no cell matched, or when cells of the base run are missing from the new "
      "one (a CI regression check)");
  compare->add_option("base", a.base_dir, "Output folder of the reference run")->required();
  compare->add_option("new", a.new_dir, "Output folder of the run to check")->required();
  compare->add_option("--tolerances", a.tolerance_file,
                      "TOML file: [tolerances] metric = { abs = ..., rel = ..., "
                      "lower_is_better = ... } overriding or adding to the defaults");
  compare->add_flag("--allow-missing", a.allow_missing,
                    "Report cells of the base run missing from the new run instead of failing "
                    "(comparing a subset on purpose)");

  CLI::App* verify = app.add_subcommand(
      "verify",
      "Check each result folder's claims (claims.toml) against its rows.csv and its README's "
      "generated verdict section; exit status 1 naming every claim that no longer holds");
  verify->add_option("dirs", a.verify_dirs, "Result folders, e.g. results/*")->required();
  verify->add_flag("--write", a.verify_write,
                   "Rewrite the README verdict sections from the claims (failures still fail)");

  CLI::App* ledger = app.add_subcommand(
      "ledger",
      "The coverage ledger: every item of the papers (results/papers.toml) with the claims that "
      "reproduce it; checks results/ledger.csv, results/LEDGER.md and the README's totals");
  ledger->add_option("--results", a.ledger_results, "The results folder (default: results)");
  ledger->add_option("--readme", a.ledger_readme,
                     "The README whose totals section to check or write (default: README.md)");
  ledger->add_flag("--write", a.ledger_write, "Write the ledger instead of checking it");

  CLI::App* contract = app.add_subcommand(
      "contract",
      "Hold techniques to the promise their describe() declares (the contract suite, as `ctest "
      "-L contract` runs it in a build): the techniques of --plugins, or those named");
  contract->add_option("--technique", a.contract_techniques, "A technique to hold (repeatable)");
  contract->add_flag("--all", a.contract_all, "Every technique, built in and loaded");
}

// The contract suite's program: installed beside the libraries, or the build tree's own.
std::string contract_program() {
  return rl::in_build_tree() ? rl::library_dir() + "/tests/relieflab-contract"
                             : rl::library_dir() + "/relieflab/relieflab-contract";
}

// `relieflab contract`: runs the contract suite on the chosen techniques, loading the same
// plugins; its exit status is the suite's.
int run_contract(const CliArgs& a, const std::vector<std::string>& plugins,
                 const std::vector<rl::LoadedPlugin>& loaded) {
  std::vector<std::string> names = a.contract_techniques;
  if (names.empty() && !a.contract_all)
    for (const rl::LoadedPlugin& p : loaded)
      names.insert(names.end(), p.techniques.begin(), p.techniques.end());
  if (names.empty() && !a.contract_all)
    throw rl::ConfigError(
        "contract: no technique to hold: load a plugin (--plugins DIR), name one (--technique "
        "NAME) or ask for --all");
  std::string filter = "--gtest_filter=";
  for (const std::string& n : names) {
    if (!rl::TechniqueRegistry::instance().find(n))
      throw rl::ConfigError("contract: no technique '" + n + "' (relieflab list names them)");
    filter += (filter.back() == '=' ? "*/" : ":*/") + n;
  }
  const std::string program = contract_program();
  if (!std::filesystem::is_regular_file(program))
    throw rl::ConfigError("contract: the contract suite is not at " + program +
                          " (it is built and installed with the tests: RELIEFLAB_BUILD_TESTS)");
  std::string path;  // the suite loads the same plugins, from a ':'-separated list
  for (const std::string& p : plugins) {
    if (p.find(':') != std::string::npos)
      throw rl::ConfigError("contract: plugin path '" + p +
                            "' holds a ':', which $RELIEFLAB_PLUGIN_PATH cannot carry");
    path += (path.empty() ? "" : ":") + p;
  }
  setenv("RELIEFLAB_PLUGIN_PATH", path.c_str(), 1);
  std::vector<char*> argv = {const_cast<char*>(program.c_str())};
  if (!a.contract_all) argv.push_back(filter.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  execv(program.c_str(), argv.data());
  throw rl::ConfigError("contract: cannot run " + program + ": " + std::strerror(errno));
}

// `relieflab ledger`: exit status 1 naming each stale file and each inconsistency.
int ledger_files(const CliArgs& a) {
  std::string report;
  const int failures =
      rl::ledger_command(a.ledger_results, a.ledger_readme, a.ledger_write, report);
  std::fputs(report.c_str(), stdout);
  std::printf("relieflab: ledger %s, %d failure(s)\n", a.ledger_write ? "written" : "checked",
              failures);
  return failures ? 1 : 0;
}

// Runs the command the arguments name; its exit status.
int run_command(const CLI::App& app, const CliArgs& a) {
  try {
    std::vector<std::string> plugins = rl::plugin_paths_from_environment();
    plugins.insert(plugins.end(), a.plugin_paths.begin(), a.plugin_paths.end());
    const std::vector<rl::LoadedPlugin> loaded = rl::load_plugins(plugins);
    if (app.got_subcommand("contract")) return run_contract(a, plugins, loaded);
    if (app.got_subcommand("list")) {
      a.markdown ? print_markdown() : print_list();
      return 0;
    }
    if (app.got_subcommand("report")) {
      const size_t n = rl::rewrite_outputs(a.report_dir);
      std::printf("relieflab: wrote %s/report.html and the tables from %zu stored rows\n",
                  a.report_dir.c_str(), n);
      return 0;
    }
    if (app.got_subcommand("status")) {
      std::fputs(rl::format_run_status(rl::run_status(a.status_dirs)).c_str(), stdout);
      return 0;
    }
    if (app.got_subcommand("merge")) {
      const rl::MergeSummary m = rl::merge_shards(a.merge_out, a.merge_shards);
      std::printf(
          "relieflab: merged %zu shard(s) into %s: %zu new rows; %zu of %zu cells "
          "present%s\n",
          m.shards, a.merge_out.c_str(), m.rows_added, m.cells - m.missing, m.cells,
          m.missing ? " (run the missing shards, or re-run into a shard's folder)" : "");
      return m.missing ? 3 : 0;
    }
    if (app.got_subcommand("compare")) {
      auto tolerances = rl::default_tolerances();
      if (!a.tolerance_file.empty()) rl::read_tolerances(a.tolerance_file, tolerances);
      rl::Comparison c = rl::compare_runs(a.base_dir, a.new_dir, tolerances);
      c.allow_missing = a.allow_missing;
      std::fputs(rl::format_comparison(c).c_str(), stdout);
      return c.failed() ? 1 : 0;
    }
    if (app.got_subcommand("verify")) return verify_folders(a.verify_dirs, a.verify_write);
    if (app.got_subcommand("ledger")) return ledger_files(a);
    if (app.got_subcommand("docs")) {
      std::printf("%d file(s) updated\n", update_docs(a.docs_root));
      return 0;
    }
    run_sweep_command(a.config_path, a.out_dir, a.quiet,
                      a.shard_option->count() ? &a.shard_text : nullptr);
    return 0;
  } catch (const rl::ConfigError& e) {
    std::fprintf(stderr, "relieflab: config error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    // Past what the estimate before the run foresaw (run/memory_estimate.h): said as such.
    std::fprintf(stderr,
                 "relieflab: error: out of memory: a setting needed more than this process may "
                 "use, past what the estimate made before the run foresaw; lower texture_res, "
                 "the viewport, a cell complex's grid or subdivide, or a curved base's segments "
                 "(rows already stored are kept; the run resumes where it stopped)\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relieflab: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ReliefLab: measure GPU relief-mapping techniques against Embree ray-traced truth.\n"
      "Sweeps views, resolutions and parameters from TOML configs and writes rows.csv,\n"
      "Markdown tables and render / truth / error images."};
  CliArgs args;
  add_commands(app, args);
  CLI11_PARSE(app, argc, argv);
  return run_command(app, args);
}
