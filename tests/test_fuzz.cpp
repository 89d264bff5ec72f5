// Seeded mutation fuzzing of what reads user input: the config parser
// (with its asset checks) and the image and mesh loaders. Each mutated input must either load
// or be refused with a ConfigError; any other exception is a failure, and the input that
// caused it is saved for the bad-input corpus. A crash ends the test binary. Each target is a
// suite of its own, so CTest runs them side by side (under the sanitizers they took 99 s in one).
//
// In the suite each target runs for a few seconds' worth of inputs; for a long run:
//   RELIEFLAB_FUZZ_SECONDS=600 ./build/tests/test_fuzz
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <unistd.h>

#include "config/config.h"
#include "core/error.h"
#include "core/triangle_mesh.h"
#include "output/compare.h"
#include "relief/image_io.h"
#include "run/asset_check.h"
#include "run/shard.h"
#include "support/test_support.h"
#include "technique/elf_check.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

const std::string kCorpus = RELIEFLAB_SOURCE_DIR "/tests/bad_inputs";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Tokens that have found bugs in configs before: non-finite and extreme numbers, paths out of
// the folder, structure.
const char* const kDictionary[] = {"nan",
                                   "inf",
                                   "-inf",
                                   "-1",
                                   "0",
                                   "1e308",
                                   "1e-308",
                                   "1e30",
                                   "\"../../x\"",
                                   "[",
                                   "]",
                                   "{",
                                   "}",
                                   "=",
                                   "\"",
                                   ",",
                                   "\n",
                                   "[[scene]]\n",
                                   "[[technique]]\n",
                                   "[[table]]\n",
                                   "[[plot]]\n",
                                   "resolution = 8192",
                                   "count = 0",
                                   "layers = 8",
                                   "proxy = \"box\"",
                                   "truth = \"mesh\"",
                                   "base = \"sphere\"",
                                   "mesh = \"assets/far.obj\"",
                                   "depth = \"assets/claims_huge.png\"",
                                   "elevations = [-45]"};

std::string mutate(std::string s, const std::vector<std::string>& seeds, std::mt19937& rng) {
  auto pick = [&](size_t n) { return n == 0 ? size_t(0) : size_t(rng() % n); };
  const int edits = rng() % 2 ? 1 : 2 + int(rng() % 3);
  for (int e = 0; e < edits; ++e) {
    const size_t at = pick(s.size() + 1);
    switch (rng() % 6) {
      case 0:  // flip a byte
        if (!s.empty()) s[pick(s.size())] ^= char(1 << (rng() % 8));
        break;
      case 1:  // delete a range
        if (!s.empty()) s.erase(at, 1 + pick(16));
        break;
      case 2:  // repeat a range
        if (!s.empty()) s.insert(at, s.substr(pick(s.size()), 1 + pick(32)));
        break;
      case 3:  // a dictionary token
        s.insert(at, kDictionary[pick(std::size(kDictionary))]);
        break;
      case 4: {  // splice in a piece of another seed
        const std::string& other = seeds[pick(seeds.size())];
        if (!other.empty()) s.insert(at, other.substr(pick(other.size()), 1 + pick(64)));
        break;
      }
      default:  // replace a number-looking character run with a dictionary token
        if (!s.empty()) {
          size_t b = pick(s.size()), end = b;
          while (end < s.size() &&
                 (std::isdigit(static_cast<unsigned char>(s[end])) || s[end] == '.'))
            ++end;
          s.replace(b, end - b, kDictionary[pick(6)]);
        }
    }
  }
  return s;
}

struct FuzzResult {
  long inputs = 0, accepted = 0, refused = 0;
  std::vector<std::string> failures;  // what went wrong, with the saved input's path
};

// Feeds mutations of `seeds` to `load` until `budget` has passed or `max_inputs` were tried.
FuzzResult fuzz(const std::string& name, const std::vector<std::string>& seeds,
                const std::function<void(const std::string&)>& load, unsigned seed,
                long max_inputs) {
  double seconds = 0;
  if (const char* s = std::getenv("RELIEFLAB_FUZZ_SECONDS")) seconds = std::atof(s);
  const auto start = std::chrono::steady_clock::now();
  const std::string saved = test::scratch_dir("fuzz-" + name + "-" + std::to_string(::getpid()));
  fs::create_directories(saved);
  std::mt19937 rng(seed);
  FuzzResult r;
  for (;; ++r.inputs) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds > 0 ? elapsed > seconds : r.inputs >= max_inputs) break;
    const std::string input = mutate(seeds[rng() % seeds.size()], seeds, rng);
    try {
      load(input);
      ++r.accepted;
    } catch (const ConfigError&) {
      ++r.refused;
    } catch (const std::exception& e) {
      const std::string path = saved + "/failure-" + std::to_string(r.failures.size());
      std::ofstream(path, std::ios::binary) << input;
      r.failures.push_back(std::string(e.what()).substr(0, 200) + " (input saved as " + path + ")");
    }
  }
  std::printf("fuzz %s: %ld inputs, %ld accepted, %ld refused with a ConfigError, %zu failures\n",
              name.c_str(), r.inputs, r.accepted, r.refused, r.failures.size());
  return r;
}

TEST(FuzzConfig, ParserAcceptsOrRefusesCleanly) {
  std::vector<std::string> seeds;
  for (const auto& e : fs::directory_iterator(kCorpus))
    if (e.path().extension() == ".toml" && fs::file_size(e.path()) < 4096)
      seeds.push_back(read_file(e.path()));
  // Valid configs too, so that mutations also reach what follows a successful parse.
  seeds.push_back(R"([sweep]
name = "good"
elevations = [45, 20]
azimuths = [30, 75]
viewports = [16, [24, 16]]
texture_res = [0, 16]
[[scene]]
name = "bricks"
relief = { procedural = "bricks", resolution = 32, options = { rows = 4, mortar = 0.1 } }
depth = 0.1
effects = ["self_shadow"]
light = [0.5, 0.5, 2]
objects = [{ shape = "sphere", center = [0.2, 0, 0.1], radius = 0.1 }]
[[scene]]
name = "sphere"
base = "sphere"
relief = { procedural = "sines", resolution = 16 }
[[technique]]
name = "relief"
linear_steps = [8, 16]
[[technique]]
name = "pom"
scenes = ["sphere"]
sets = [{ min_samples = 8, max_samples = 16 }]
[[table]]
rows = ["scene", "technique"]
columns = ["elevation_deg"]
values = ["wrong_pct", "fetches_mean"]
aggregate = "mean"
[[plot]]
x = "frame_ms"
group = ["scene"]
)");
  seeds.push_back(read_file(RELIEFLAB_SOURCE_DIR "/configs/papers/baboud2006-fig12.toml"));
  // Half of the inputs start from a valid config (the corpus is mostly refusals).
  const std::vector<std::string> good(seeds.end() - 2, seeds.end());
  for (size_t n = seeds.size(); n > 0; n -= std::min(n, good.size()))
    seeds.insert(seeds.end(), good.begin(), good.end());
  const FuzzResult r = fuzz(
      "config", seeds,
      [](const std::string& text) {
        // Relative paths resolve in the corpus folder, where its assets are.
        check_sweep_assets(parse_sweep_config(text, "fuzz.toml", kCorpus));
      },
      1, 3000);
  EXPECT_GT(r.refused, 0);
  for (const std::string& f : r.failures) ADD_FAILURE() << f;
}

TEST(FuzzInputFiles, ImageAndMeshLoadersAcceptOrRefuseCleanly) {
  const std::string dir = test::scratch_dir("fuzz-files-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<float> px(16 * 16 * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 7) / 6.0f;
  write_png(dir + "/seed.png", 16, 16, 4, px);
  const std::vector<std::string> images = {read_file(dir + "/seed.png"),
                                           read_file(kCorpus + "/assets/claims_huge.png")};
  const FuzzResult ri = fuzz(
      "image", images,
      [&](const std::string& bytes) {
        std::ofstream(dir + "/input.png", std::ios::binary | std::ios::trunc) << bytes;
        ReliefImageSource src;
        src.normal_path = dir + "/input.png";
        load_relief_images(src, 1.0);
      },
      2, 400);
  const std::vector<std::string> meshes = {
      read_file(kCorpus + "/assets/far.obj"), read_file(kCorpus + "/assets/nan.obj"),
      read_file(kCorpus + "/assets/base_uv_nan.obj"),
      read_file(kCorpus + "/assets/base_uv_huge.obj"),
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
      "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n"};
  const FuzzResult rm = fuzz(
      "mesh", meshes,
      [&](const std::string& text) {
        std::ofstream(dir + "/input.obj", std::ios::trunc) << text;
        load_mesh(dir + "/input.obj");
      },
      3, 400);
  // PLY, which Assimp reads by the header's counts and the faces' indices (a bad index crashed
  // the process): ASCII and binary seeds, their headers, counts and indices mutated.
  const std::vector<std::string> plys = {
      read_file(kCorpus + "/assets/declares_more_faces.ply"),
      read_file(kCorpus + "/assets/declares_more_faces_binary.ply"),
      read_file(kCorpus + "/assets/face_past_vertices.ply"),
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0 1 2\n3 1 3 2\n"};
  const FuzzResult rp = fuzz(
      "ply", plys,
      [&](const std::string& bytes) {
        std::ofstream(dir + "/input.ply", std::ios::binary | std::ios::trunc) << bytes;
        load_mesh(dir + "/input.ply");
      },
      4, 400);
  for (const std::string& f : ri.failures) ADD_FAILURE() << f;
  for (const std::string& f : rm.failures) ADD_FAILURE() << f;
  for (const std::string& f : rp.failures) ADD_FAILURE() << f;
}

// A plugin file damaged in its structure (hostile input, round four: one cut short killed every
// command with SIGBUS): the ELF header's table offsets and counts and the program headers'
// offsets and sizes set to extreme values, or the file cut at any length. `relieflab --plugins
// FILE list` must refuse it with exit 2 (or, untouched where it counts, load it), never die of
// a signal. Each input runs in its own process, as a bad plugin would end it.
TEST(FuzzPlugins, FilesDamagedInTheirStructureAreRefusedNotFatal) {
  const std::string seed_file =
      fs::canonical(fs::path(RELIEFLAB_CLI).parent_path() / "librelieflab_stb.so").string();
  const std::string seed = read_file(seed_file);
  ASSERT_GT(seed.size(), 4096u);
  const std::string dir = test::scratch_dir("fuzz-plugin-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto u64 = [&](const std::string& b, size_t at) {
    uint64_t v = 0;
    std::memcpy(&v, b.data() + at, 8);
    return v;
  };
  const uint64_t phoff = u64(seed, 32);
  const uint16_t phnum = uint16_t(uint8_t(seed[56]) | uint8_t(seed[57]) << 8);
  std::mt19937 rng(7);
  const uint64_t extremes[] = {0,
                               1,
                               0x7fffffffffffffffull,
                               ~0ull,
                               seed.size(),
                               seed.size() + 1,
                               ~0ull - 4095,
                               uint64_t(seed.size()) * 4096};
  int failures = 0, refused_here = 0, inputs = 0;
  const char* seconds = std::getenv("RELIEFLAB_FUZZ_SECONDS");
  const auto start = std::chrono::steady_clock::now();
  auto more = [&](int i) {
    if (!seconds) return i < 120;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
           std::atof(seconds);
  };
  for (int i = 0; more(i) && failures < 5; ++i, ++inputs) {
    std::string bytes = seed;
    if (i % 4 == 3) {
      bytes.resize(rng() % seed.size());  // cut short anywhere
    } else {
      // A header field (table offsets, sizes and counts) or a program header's offset, sizes
      // or address, 8 bytes at a time (2 for the counts), set to an extreme value.
      std::vector<std::pair<size_t, size_t>> fields = {{32, 8}, {40, 8}, {54, 2}, {56, 2},
                                                       {58, 2}, {60, 2}, {62, 2}};
      for (uint16_t k = 0; k < phnum; ++k)
        for (size_t f : {8, 16, 32, 40, 48}) fields.push_back({phoff + k * 56 + f, 8});
      const auto [at, width] = fields[rng() % fields.size()];
      const uint64_t value = extremes[rng() % std::size(extremes)];
      std::memcpy(bytes.data() + at, &value, width);
    }
    const std::string path = dir + "/plugin-" + std::to_string(i) + ".so";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    // What the structural check refuses never reaches the loader: checked here, the CLI's own
    // first step (technique/plugins.cpp), and only every eighth such input also through the
    // CLI, whose exit on it is then 2. What it lets through is loaded in a CLI process of its
    // own, where a crash cannot end the test. (Each CLI process cost 0.4 s sanitized.)
    bool refused = false;
    try {
      check_elf_is_whole(path);
    } catch (const ConfigError&) {
      refused = true;
    }
    if (refused && i % 8 != 0) {
      ++refused_here;
      fs::remove(path);
      continue;
    }
    std::string out;
    const int code = test::run_cli("--plugins " + path + " list", out);
    if (refused && code != 2) ADD_FAILURE() << path << ": refused by the check, exit " << code;
    if (code != 2 && code != 0) {
      ++failures;
      ADD_FAILURE() << path << ": exit " << code << " (a signal?): " << out.substr(0, 300);
    } else {
      fs::remove(path);
    }
  }
  std::printf("fuzz plugins: %d inputs, %d refused by the check alone, %d through the CLI\n",
              inputs, refused_here, inputs - refused_here);
}

// The structural check must not refuse what linkers write: every shared object this test
// program has loaded (ReliefLab's libraries, Mesa, Embree, glibc's, ... built by GNU ld and
// others) passes it.
TEST(FuzzPlugins, EverySharedObjectThisProcessLoadedPassesThePluginCheck) {
  std::ifstream maps("/proc/self/maps");
  std::set<std::string> objects;
  for (std::string line; std::getline(maps, line);) {
    const size_t slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    if (path.find(".so") != std::string::npos && fs::is_regular_file(path)) objects.insert(path);
  }
  ASSERT_GT(objects.size(), 10u);
  for (const std::string& path : objects) EXPECT_NO_THROW(check_elf_is_whole(path)) << path;
}

// The commands that read a finished run (hostile input, second round): status, compare, report and
// merge, on a run folder whose sweep.json or results.sqlite is damaged byte by byte. Each must
// finish with the folder's outputs rewritten or refuse with a ConfigError, or an error naming the
// damaged store; anything else is a failure. A crash ends the test binary; a hang, its CTest
// timeout.
TEST(FuzzRunFolders, StatusCompareReportAndMergeFailCleanly) {
  const std::string dir = test::scratch_dir("fuzz-runs-" + std::to_string(::getpid()));
  test::run_sweep_in(R"(
[sweep]
name = "fuzzed"
views = [[45, 30], [20, 30]]
viewports = [16]
frames = 1
warmup = 0
images = false
[[scene]]
name = "bricks"
relief = { procedural = "bricks", resolution = 16 }
[[technique]]
name = "relief"
linear_steps = [4, 8]
)",
                     dir);
  const std::string run = dir + "/out";
  const std::string record = read_file(run + "/sweep.json");
  const std::string store = read_file(run + "/results.sqlite");
  long input = 0;
  auto commands = [&](const std::string& bytes, const char* file) {
    const std::string damaged = dir + "/damaged-" + std::to_string(input++ % 4);
    fs::remove_all(damaged);
    fs::copy(run, damaged, fs::copy_options::recursive);
    std::ofstream(damaged + "/" + file, std::ios::binary | std::ios::trunc) << bytes;
    try {
      run_status({damaged});
      compare_rows(read_run_rows(run), read_run_rows(damaged), default_tolerances());
      rewrite_outputs(damaged);
      fs::remove_all(damaged + "-merged");
      merge_shards(damaged + "-merged", {damaged});
    } catch (const std::runtime_error& e) {
      // A store SQLite cannot read names its file; anything else propagates as a failure.
      if (dynamic_cast<const ConfigError*>(&e) ||
          std::string(e.what()).find(damaged) == std::string::npos)
        throw;
      throw ConfigError(e.what());
    }
  };
  const FuzzResult rr = fuzz(
      "record", {record}, [&](const std::string& b) { commands(b, "sweep.json"); }, 5, 60);
  const FuzzResult rs = fuzz(
      "store", {store}, [&](const std::string& b) { commands(b, "results.sqlite"); }, 6, 60);
  for (const std::string& f : rr.failures) ADD_FAILURE() << f;
  for (const std::string& f : rs.failures) ADD_FAILURE() << f;
  EXPECT_GT(rr.refused, 0);
  EXPECT_GT(rs.refused + rs.accepted, 0);
}

}  // namespace
}  // namespace rl
