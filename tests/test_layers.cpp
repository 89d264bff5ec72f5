// The harness's folders form layers, each including only those below it: core; gl, relief and
// metrics on core; the image module (oiio) on relief's interface to it; scene on relief; truth
// on scene; the GPU's copies of a scene (gpu) on gl and scene; technique (the plugin API) on
// gpu; a sweep's config on technique; its output (store, tables, report) on
// config and metrics; its run on output and truth; claims (verdicts checked against a sweep's
// rows) on output; the CLI on top. A cycle (relief <-> scene once did) fails here, naming the
// file and include. The build enforces the layers too (cmake/ReliefLabLayers.cmake); this test
// holds each folder to the layers it may include directly.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

TEST(Layers, HarnessFoldersIncludeOnlyTheLayersBelowThem) {
  const std::map<std::string, std::set<std::string>> allowed = {
      {"core", {"core"}},
      {"gl", {"core", "gl"}},
      {"relief", {"core", "relief"}},
      {"oiio", {"relief"}},  // the image module: relief/image_backend.h through OpenImageIO
      {"stb", {"relief"}},   // its fallback through Debian's stb
      {"metrics", {"core", "metrics"}},
      {"scene", {"core", "relief", "scene"}},
      {"truth", {"core", "relief", "scene", "truth"}},
      {"gpu", {"core", "gl", "relief", "scene", "gpu"}},
      {"technique", {"core", "gl", "relief", "scene", "gpu", "technique"}},
      {"config", {"core", "gl", "relief", "scene", "technique", "config"}},
      {"output", {"core", "relief", "scene", "metrics", "technique", "config", "output"}},
      {"run",
       {"core", "gl", "relief", "scene", "metrics", "truth", "gpu", "technique", "config", "output",
        "run"}},
      {"claims", {"core", "config", "output", "claims"}},
      {"cli",
       {"core", "gl", "relief", "scene", "metrics", "truth", "gpu", "technique", "config", "output",
        "run", "claims"}},
  };
  const fs::path harness = fs::path(RELIEFLAB_SOURCE_DIR) / "harness";
  const std::regex include(R"re(^\s*#\s*include\s+"([a-z_]+)/)re");
  int files = 0, includes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(harness)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".h" && ext != ".cpp") continue;
    const std::string folder = fs::relative(entry.path(), harness).begin()->string();
    ASSERT_TRUE(allowed.count(folder)) << "harness/" << folder << " has no layer: add it here";
    ++files;
    std::ifstream in(entry.path());
    int line_no = 0;
    for (std::string line; std::getline(in, line);) {
      ++line_no;
      std::smatch m;
      if (!std::regex_search(line, m, include)) continue;
      ++includes;
      EXPECT_TRUE(allowed.at(folder).count(m[1].str()))
          << fs::relative(entry.path(), harness).string() << ":" << line_no << " includes "
          << m[1].str() << "/ from the " << folder << " layer";
    }
  }
  EXPECT_GT(files, 50);
  EXPECT_GT(includes, 100);
}

// Image files go through a module loaded on first use (relief/image_backend.h): the CLI itself
// must not need OpenImageIO, whose ~260 libraries cost every process 0.2 s at start.
TEST(Layers, TheCliDoesNotLinkOpenImageIO) {
  const std::string cmd = std::string("ldd ") + RELIEFLAB_CLI + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[4096];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  ASSERT_EQ(pclose(pipe), 0) << out;
  EXPECT_NE(out.find("libc.so"), std::string::npos) << out;  // ldd did list the libraries
  EXPECT_EQ(out.find("OpenImageIO"), std::string::npos) << out;
}

}  // namespace
