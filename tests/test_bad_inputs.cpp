// The bad-input corpus (tests/bad_inputs/): every hostile config is refused before
// any work with one clear line naming the config file and what is wrong.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include "core/atomic_write.h"
#include "core/triangle_mesh.h"

#include "config/config.h"
#include "core/error.h"
#include "output/outputs_record.h"
#include "relief/image_io.h"
#include "run/asset_check.h"
#include "run/cells.h"
#include "run/memory_estimate.h"
#include "support/test_support.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

const std::string kCorpus = RELIEFLAB_SOURCE_DIR "/tests/bad_inputs";

std::vector<fs::path> corpus_configs() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kCorpus))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> expectations(const fs::path& file) {
  std::vector<std::string> expect;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line) && line.rfind("# expect: ", 0) == 0;)
    expect.push_back(line.substr(10));
  return expect;
}

TEST(BadInputs, EveryCorpusInputIsRefusedWithAClearMessage) {
  const std::vector<fs::path> files = corpus_configs();
  ASSERT_GE(files.size(), 25u);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const std::vector<std::string> expect = expectations(file);
    ASSERT_FALSE(expect.empty()) << "no '# expect:' line";
    std::string message;
    try {
      const SweepConfig config = load_sweep_config(file.string());
      check_sweep_assets(config);
      refuse_cells_beyond_memory(config, expand_cells(config));
    } catch (const ConfigError& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_EQ(message.rfind(file.string(), 0), 0u) << "does not start with the file: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(message.size(), 600u) << message.substr(0, 600);
    for (const std::string& e : expect)
      EXPECT_NE(message.find(e), std::string::npos) << "expected '" << e << "' in: " << message;
  }
}

// The asset check remembers images that loaded cleanly, by their bytes: the same image cut short
// in place afterwards (its header whole, so the config still parses) is refused, not passed
// from memory.
TEST(BadInputs, AnImageCutShortAfterACleanCheckIsRefused) {
  const std::string dir = test::scratch_dir("cut-after-check");
  fs::create_directories(dir);
  const std::string png = dir + "/depth.png";
  std::vector<float> pixels(64 * 64 * 3);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = float((i * 37) % 101) / 100.0f;
  write_png(png, 64, 64, 3, pixels);
  const std::string text =
      "[sweep]\nname = \"cut\"\n[[scene]]\nname = \"s\"\nrelief = { depth = \"depth.png\" }\n"
      "[[technique]]\nname = \"relief\"\n";
  EXPECT_NO_THROW(check_sweep_assets(parse_sweep_config(text, dir + "/cut.toml", dir)));
  fs::resize_file(png, fs::file_size(png) / 2);
  const SweepConfig cut = parse_sweep_config(text, dir + "/cut.toml", dir);
  EXPECT_THROW(check_sweep_assets(cut), ConfigError);
}

// Mistakes on the command line (hostile input, second round): an empty --shard ran every cell; a
// device as the config gave a raw filesystem error. Both are refused naming what was given.
TEST(BadInputs, CommandLineMistakesAreRefused) {
  std::string out;
  const std::string config = kCorpus + "/../shard_sweep.toml";
  EXPECT_EQ(test::run_cli(
                "run " + config + " --shard '' -q --out " + test::scratch_dir("empty-shard"), out),
            2)
      << out;
  EXPECT_NE(out.find("--shard '': give I/N"), std::string::npos) << out;
  EXPECT_EQ(test::run_cli("run /dev/zero", out), 2) << out;
  EXPECT_NE(out.find("/dev/zero: is not a regular file"), std::string::npos) << out;
  // A byte that is not UTF-8 in --out failed after the whole sweep (JSON holds only UTF-8):
  // refused before anything is measured or created.
  const std::string latin1 = test::scratch_dir("latin1") + "/caf\xE9";
  EXPECT_EQ(test::run_cli("run " + config + " -q --out '" + latin1 + "'", out), 2) << out;
  EXPECT_NE(out.find("the output folder"), std::string::npos) << out;
  EXPECT_NE(out.find("caf\\xE9 is not valid UTF-8"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(latin1));
}

// A shared object cut short killed every command with SIGBUS when the plugin path named it
// (the loader maps the segments its header declares): refused naming the file, no signal.
TEST(BadInputs, ATruncatedPluginIsRefusedNotFatal) {
  const fs::path library =
      fs::canonical(fs::path(RELIEFLAB_CLI).parent_path() / "librelieflab_core.so");
  const fs::path folder = test::scratch_dir("truncated-plugin");
  fs::create_directories(folder);
  const fs::path cut = folder / "cut.so";
  fs::copy_file(library, cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, fs::file_size(library) / 2);
  std::string out;
  EXPECT_EQ(test::run_cli("--plugins " + cut.string() + " list", out), 2) << out;
  EXPECT_NE(out.find("not a whole shared object"), std::string::npos) << out;
  EXPECT_NE(out.find("cut.so"), std::string::npos) << out;
}

// `verify` could be fooled (hostile input, round four): a folder that does not exist passed, a
// check that holds whatever the rows say was accepted, and a second verdict section appended
// to the README passed unread.
TEST(BadInputs, VerifyCannotBeFooled) {
  const fs::path dir = test::scratch_dir("verify-fooled");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string rows = "technique,wrong_pct\nrelief,5\n";
  std::ofstream(dir / "rows.csv") << rows;
  write_outputs_record(dir.string(), {{"rows.csv", rows}});  // as the run that wrote them
  auto claims = [&](const std::string& check) {
    std::ofstream(dir / "claims.toml", std::ios::trunc)
        << "[[claim]]\nid = \"c\"\njudges = \"j\"\nverdict = \"confirmed\"\n"
           "text = \"wrong {w}%\"\n[claim.values]\n"
           "w = { where = \"technique=relief\", column = \"wrong_pct\", of = \"mean\" }\n"
           "[[claim.check]]\nthat = \""
        << check << "\"\n";
  };
  const std::string section = "<!-- claims: generated from claims.toml -->\n<!-- claims: end -->\n";
  std::ofstream(dir / "README.md") << "# A folder\n\n" << section;
  std::string out;
  claims("w < 10");
  ASSERT_EQ(test::run_cli("verify --write " + dir.string(), out), 0) << out;
  ASSERT_EQ(test::run_cli("verify " + dir.string(), out), 0) << out;

  EXPECT_EQ(test::run_cli("verify " + (dir / "missing").string(), out), 2) << out;
  EXPECT_NE(out.find("missing: no such folder"), std::string::npos) << out;

  std::ofstream(dir / "README.md", std::ios::app) << "\n" << section;
  EXPECT_EQ(test::run_cli("verify " + dir.string(), out), 1) << out;
  EXPECT_NE(out.find("more than one generated verdict section"), std::string::npos) << out;

  for (const char* check : {"1 < 2", "w <= w", "w between 1 and w"}) {
    claims(check);
    EXPECT_EQ(test::run_cli("verify " + dir.string(), out), 2) << check << ": " << out;
    EXPECT_NE(out.find("holds whatever the rows say"), std::string::npos) << check << ": " << out;
  }
}

// Nothing a run writes may go through a link one folder down (a planted images/<scene> made it
// write its pictures into another folder), nor over the config it was given (kept in --out
// under a name the run writes).
TEST(BadInputs, ARunWritesThroughNoLinkAndOverNoConfig) {
  const std::string config = kCorpus + "/../shard_sweep.toml";
  const fs::path out = test::scratch_dir("planted-link");
  const fs::path elsewhere = test::scratch_dir("planted-link-target");
  fs::remove_all(out);
  fs::remove_all(elsewhere);
  fs::create_directories(out / "images");
  fs::create_directories(elsewhere);
  fs::create_directory_symlink(elsewhere, out / "images" / "bricks");
  std::string text;
  EXPECT_EQ(test::run_cli("run " + config + " -q --out " + out.string(), text), 2) << text;
  EXPECT_NE(text.find("images/bricks is a symbolic link"), std::string::npos) << text;
  EXPECT_TRUE(fs::is_empty(elsewhere));

  fs::remove_all(out);
  fs::create_directories(out);
  fs::copy_file(config, out / "rows.csv");
  const std::string kept = out.string() + "/rows.csv";
  EXPECT_EQ(test::run_cli("run " + kept + " -q --out " + out.string(), text), 2) << text;
  EXPECT_NE(text.find("where the run writes 'rows.csv': it would be overwritten"),
            std::string::npos)
      << text;
  std::ifstream original(config), after(kept);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(original), {}),
            std::string(std::istreambuf_iterator<char>(after), {}));
}

// FIFOs reached indirectly hung the reader: an OBJ's material library, the tolerance file of
// `compare`, a file the claims read. Each is refused naming it, without blocking (a hang here
// would end at the test's timeout). A FIFO in the precompute cache is a cache miss.
TEST(BadInputs, FifosReachedIndirectlyAreRefusedNotWaitedOn) {
  const fs::path dir = test::scratch_dir("fifos");
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir / "pipe.mtl").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir / "tolerances.toml").c_str(), 0600), 0);
  std::ofstream(dir / "tri.obj") << "mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  try {
    load_mesh((dir / "tri.obj").string());
    ADD_FAILURE() << "loaded an OBJ whose material library is a FIFO";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("pipe.mtl is not a regular file"), std::string::npos)
        << e.what();
  }
  std::string out;
  EXPECT_EQ(test::run_cli("compare " + dir.string() + " " + dir.string() + " --tolerances " +
                              (dir / "tolerances.toml").string(),
                          out),
            2)
      << out;
  EXPECT_NE(out.find("tolerances.toml: the tolerance file is not a regular file"),
            std::string::npos)
      << out;
  ASSERT_EQ(::mkfifo((dir / "README.md").c_str(), 0600), 0);
  try {
    read_text((dir / "README.md").string());
    ADD_FAILURE() << "read a FIFO as text";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("README.md: not a regular file"), std::string::npos);
  }
}

// A cost model that is a FIFO is named as what it is (it exists: "no model file" misled), and
// never opened; a config whose read fails is named, not parsed as the part read before it.
TEST(BadInputs, ACostModelFifoAndAnUnreadableConfigAreNamed) {
  const fs::path dir = test::scratch_dir("model_fifo");
  fs::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir / "model.toml").c_str(), 0600), 0);
  const std::string text =
      "[sweep]\nname = \"bad\"\nelevations = [45]\ncost_model = \"model.toml\"\n"
      "[[scene]]\nname = \"flat\"\nrelief = { procedural = \"sines\", resolution = 8 }\n"
      "[[technique]]\nname = \"relief\"\n";
  try {
    parse_sweep_config(text, (dir / "sweep.toml").string(), dir.string());
    ADD_FAILURE() << "accepted a FIFO as the cost model";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("model.toml is not a regular file"), std::string::npos)
        << e.what();
  }
  try {
    load_sweep_config("/proc/self/mem");  // a regular file whose every read fails (EIO)
    ADD_FAILURE() << "read /proc/self/mem as a config";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/self/mem: cannot read ("), std::string::npos)
        << e.what();
  }
}

// The fallback image module (the relocatable package's) reads no file cut short as a whole one:
// stb fills the missing part with zeros, so it reads only formats it can check (a TGA of 20
// bytes, or half of one, ran as a map before), and an uncompressed BMP is held to its header.
TEST(BadInputs, TheFallbackImageModuleRefusesFilesCutShort) {
  const std::string corpus = std::string(RELIEFLAB_TEST_DIR) + "/bad_inputs/assets/";
  const std::string stb = fs::path(RELIEFLAB_CLI).parent_path().string() + "/librelieflab_stb.so";
  const fs::path dir = test::scratch_dir("stb_cut");
  fs::create_directories(dir);
  for (const auto& [file, expect] : std::vector<std::pair<std::string, std::string>>{
           {"tiny.tga", "reads PNG, JPEG, BMP and Radiance HDR files, and this is none of them"},
           {"half.tga", "reads PNG, JPEG, BMP and Radiance HDR files, and this is none of them"},
           {"truncated.bmp", "a BMP cut short: 2000 bytes where its header needs 66614"}}) {
    const std::string config = (dir / (file + ".toml")).string();
    std::ofstream(config) << "[sweep]\nname = \"cut\"\nelevations = [45]\nviewports = [16]\n"
                             "[[scene]]\nname = \"cut\"\nrelief = { depth = \""
                          << corpus << file << "\" }\n[[technique]]\nname = \"relief\"\n";
    std::string out;
    EXPECT_EQ(test::run_cli("run " + config + " --out " + (dir / "out").string() + " -q", out,
                            "env RELIEFLAB_IMAGE_MODULE=" + stb + " "),
              2)
        << out;
    EXPECT_NE(out.find(expect), std::string::npos) << file << ": " << out;
  }
}

// The memory a cell may use is what this process may use, not what the machine has: under an
// address-space limit (ulimit -v; a cgroup's memory.max reads the same way) a sweep the limit
// cannot hold is refused before anything is written, naming the limit.
TEST(BadInputs, ASweepBeyondTheProcesssMemoryLimitIsRefusedUpFront) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no limit can hold it";
#endif
  const fs::path dir = test::scratch_dir("rlimit");
  fs::create_directories(dir);
  std::ofstream(dir / "big.toml")
      << "[sweep]\nname = \"big\"\nelevations = [45]\nviewports = [4096]\n"
         "[[scene]]\nname = \"flat\"\nrelief = { procedural = \"sines\", resolution = 16 }\n"
         "[[technique]]\nname = \"relief\"\n";
  std::string out;
  EXPECT_EQ(test::run_cli(
                "run " + (dir / "big.toml").string() + " --out " + (dir / "out").string() + " -q",
                out, "prlimit --as=3221225472 "),
            2)
      << out;
  EXPECT_NE(out.find("needs about 5.9 GiB, mostly its G-buffers (5.9 GiB), and this process may "
                     "use (its address-space limit, ulimit -v) 3.0 GiB"),
            std::string::npos)
      << out;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// A cell complex's subdivide multiplies its mesh by 4^k: the estimate counts the mesh so (a
// million triangles at subdivide 4 ended in a bare bad_alloc after minutes).
TEST(BadInputs, TheMemoryEstimateCountsASubdividedMesh) {
  auto estimate = [](int subdivide) {
    const std::string text =
        "[sweep]\nname = \"s\"\nelevations = [45]\nviewports = [16]\n[[scene]]\nname = "
        "\"bunny\"\nrelief = { cells = \"" +
        std::string(RELIEFLAB_SOURCE_DIR) +
        "/assets/meshes/bunny.obj\", up = \"y\", grid = 2, resolution = 8, subdivide = " +
        std::to_string(subdivide) + " }\n[[technique]]\nname = \"cell_complex\"\n";
    const SweepConfig config = parse_sweep_config(text, "s.toml", ".");
    return estimate_cell_memory(config, expand_cells(config).front()).bytes;
  };
  // The bunny's 3,674 triangles, 256 times over at subdivide 4, at no less than 80 bytes each.
  EXPECT_GE(estimate(4) - estimate(0), 3674.0 * 255 * 80);
}

// verify and ledger read whatever file they are pointed at: a README of 300 MiB (sparse here,
// so it costs no disk) is refused by size, not read whole into memory.
TEST(BadInputs, AHugeTextFileIsRefusedNotReadWhole) {
  const fs::path dir = test::scratch_dir("huge-readme");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "README.md").close();
  fs::resize_file(dir / "README.md", uintmax_t(300) << 20);
  try {
    read_text((dir / "README.md").string());
    ADD_FAILURE() << "read a 300 MiB file whole";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("README.md"), std::string::npos) << e.what();
  }
  // A ledger of one item, consistent, so that the command reaches the README.
  std::ofstream(dir / "papers.toml")
      << "[[paper]]\nid = \"p\"\ncite = \"A paper\"\n[[paper.item]]\nid = \"a\"\n"
         "what = \"Table 1\"\ngap = \"not yet run\"\n";
  std::string out;
  EXPECT_EQ(
      test::run_cli(
          "ledger --results " + dir.string() + " --readme " + (dir / "README.md").string(), out),
      2)
      << out;
  EXPECT_NE(out.find("README.md"), std::string::npos) << out;
}

}  // namespace
}  // namespace rl
