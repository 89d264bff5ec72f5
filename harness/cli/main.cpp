// relieflab: run config-driven sweeps of relief-mapping techniques against Embree truth.
//   relieflab run [CONFIG] [--out DIR]   run a sweep (the built-in default without CONFIG)
//   relieflab list                       techniques with citation, effects and parameters
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "relief/procedural.h"
#include "sweep/config.h"
#include "sweep/runner.h"
#include "technique/technique.h"

namespace {

void print_list() {
  const auto& registry = rl::TechniqueRegistry::instance();
  for (const std::string& name : registry.names()) {
    const rl::TechniqueInfo& info = registry.find(name)->info;
    std::printf("%s — %s\n  citation: %s\n  effects:  %s\n", info.name.c_str(), info.title.c_str(),
                info.citation.c_str(), rl::join_effects(info.effects).c_str());
    std::printf("  proxies:  base%s\n", info.box_proxy ? ", box" : "");
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
      std::printf("            %s = %g: %s\n", o.name.c_str(), o.default_value, o.doc.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ReliefLab: measure GPU relief-mapping techniques against Embree ray-traced truth.\n"
      "Sweeps views, resolutions and parameters from TOML configs and writes rows.csv,\n"
      "Markdown tables and render / truth / error images."};
  app.require_subcommand(1);

  std::string config_path, out_dir;
  bool quiet = false;
  CLI::App* run =
      app.add_subcommand("run", "Run a sweep (the built-in default sweep without CONFIG)");
  run->add_option("config", config_path, "Sweep config (TOML), e.g. configs/default.toml");
  run->add_option("-o,--out", out_dir,
                  "Output folder (default: out/<sweep name>); re-running into it resumes");
  run->add_flag("-q,--quiet", quiet, "No per-cell progress lines");

  app.add_subcommand("list",
                     "List techniques (citation, effects, parameters) and procedural reliefs");

  CLI11_PARSE(app, argc, argv);

  try {
    if (app.got_subcommand("list")) {
      print_list();
      return 0;
    }
    rl::SweepConfig config =
        config_path.empty() ? rl::default_sweep_config() : rl::load_sweep_config(config_path);
    rl::RunOptions options;
    options.out_dir = out_dir.empty() ? "out/" + config.name : out_dir;
    options.progress = !quiet;
    rl::run_sweep(config, options);
    return 0;
  } catch (const rl::ConfigError& e) {
    std::fprintf(stderr, "relieflab: config error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relieflab: error: %s\n", e.what());
    return 1;
  }
}
