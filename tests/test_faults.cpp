// Faults while writing and reading results (hostile input, first round): a write the disk
// refuses stops with a clear error and leaves nothing under the final name; runs writing into
// one output folder at once do not trip over each other's temporary files; a corrupt stored
// row is dropped with a warning and its cell measured again.
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "core/atomic_write.h"
#include "relief/image_io.h"
#include "support/test_support.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

// Runs `write` in a child process whose files may not grow beyond `limit` bytes (a full disk,
// as the process sees it). Returns the child's exit code: 0 = the write threw a
// std::runtime_error, 1 = it did not throw, 2 = another exception.
int under_file_size_limit(rlim_t limit, const std::function<void()>& write) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);  // a write past the limit then fails with EFBIG
    rlimit r{limit, limit};
    setrlimit(RLIMIT_FSIZE, &r);
    try {
      write();
    } catch (const std::runtime_error&) {
      _exit(0);
    } catch (...) {
      _exit(2);
    }
    _exit(1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 3;
}

// Nothing but `keep` in `dir`: no temporary file left behind.
std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

TEST(Faults, AFullDiskStopsTheWriteAndLeavesNoFile) {
  const std::string dir = test::scratch_dir("full-disk");
  fs::create_directories(dir);
  // Noise does not compress: a 256 x 256 RGB PNG is about 200 KB, far past the 16 KB limit.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<float> noise(256 * 256 * 3);
  for (float& v : noise) v = u(rng);
  EXPECT_EQ(
      under_file_size_limit(16384, [&] { write_png(dir + "/image.png", 256, 256, 3, noise); }), 0);
  EXPECT_EQ(under_file_size_limit(
                16384, [&] { write_text_atomic(dir + "/rows.csv", std::string(100000, 'x')); }),
            0);
  EXPECT_TRUE(files_in(dir).empty()) << "left behind: " << files_in(dir).front();
  // The same writes with room succeed and read back.
  write_png(dir + "/image.png", 256, 256, 3, noise);
  write_text_atomic(dir + "/rows.csv", "a,b\n");
  EXPECT_EQ(files_in(dir).size(), 2u);
}

// Three runs of one sweep into one folder at once: each exits 0, and the folder holds one row
// per cell and every image whole.
TEST(Faults, ConcurrentRunsIntoOneFolderAllSucceed) {
  const std::string dir = test::scratch_dir("concurrent");
  const std::string config = test::write_small_sweep(dir, "");
  const std::string out = dir + "/out";
  int codes[3] = {-1, -1, -1};
  std::string outputs[3];
  std::vector<std::thread> runs;
  for (int i = 0; i < 3; ++i)
    runs.emplace_back([&, i] {
      codes[i] = test::run_cli("run " + config + " --out " + out + " -q", outputs[i]);
    });
  for (auto& t : runs) t.join();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(codes[i], 0) << outputs[i];
  std::ifstream csv(out + "/rows.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 1 + 4);  // header + 2 views x 2 settings
  int images = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "left behind: " << e.path();
    if (e.path().extension() == ".png") {
      ++images;
      auto in = OIIO::ImageInput::open(e.path().string());
      ASSERT_TRUE(in) << e.path();
      std::vector<unsigned char> px(in->spec().image_bytes());
      EXPECT_TRUE(in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::UINT8, px.data()))
          << e.path();
    }
  }
  EXPECT_GT(images, 0);
}

TEST(Faults, CorruptStoredRowsAreMeasuredAgainWithAWarning) {
  const std::string dir = test::scratch_dir("corrupt-store");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out", db = out + "/results.sqlite";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  // A row cut short, and one whose measure is text.
  test::store_exec(db, "UPDATE rows SET row = '{\"truncated' WHERE rowid = 1");
  test::store_exec(
      db, "UPDATE rows SET row = json_set(row, '$.pos_err_rmse', 'banana') WHERE rowid = 2");
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  EXPECT_NE(output.find("is not valid JSON"), std::string::npos) << output;
  EXPECT_NE(output.find("holds a non-number in 'pos_err_rmse'"), std::string::npos) << output;
  EXPECT_NE(output.find("2 already in"), std::string::npos) << output;  // 4 cells, 2 kept
  std::ifstream csv(out + "/rows.csv");
  std::string header, line;
  std::getline(csv, header);
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(line.find("banana"), std::string::npos) << line;
    EXPECT_EQ(line.rfind("relief,bricks,", 0), 0u) << line;  // identity columns present
  }
  EXPECT_EQ(rows, 4);
}

// A store measured by another version of the measurement (every key differs): `report` would
// have nothing to lay out, and must not overwrite the folder's tables with empty ones.
TEST(Faults, ReportRefusesAStoreOfAnotherMeasurementVersion) {
  const std::string dir = test::scratch_dir("old-store");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  std::ifstream before_file(out + "/rows.csv");
  const std::string before((std::istreambuf_iterator<char>(before_file)), {});
  test::store_exec(out + "/results.sqlite", "UPDATE rows SET key = 'v0-' || key");
  EXPECT_NE(test::run_cli("report " + out, output), 0) << output;
  EXPECT_NE(output.find("none under this sweep's cell keys"), std::string::npos) << output;
  std::ifstream after_file(out + "/rows.csv");
  const std::string after((std::istreambuf_iterator<char>(after_file)), {});
  EXPECT_EQ(after, before);
  EXPECT_NE(before.find("relief,bricks,"), std::string::npos);
}

// Hostile input, second round: a link planted in the output folder under a name the run owns would
// send the log (or the pictures) outside it, and a FIFO as the log hung `report`. The run,
// `report` and `merge` refuse such a folder before writing anything, naming the entry.
TEST(Faults, LinksAndDevicesPlantedInTheOutputFolderAreRefused) {
  const std::string dir = test::scratch_dir("planted");
  const std::string config = test::write_small_sweep(dir, "images = true\n");
  const std::string outside = dir + "/outside.txt";
  std::ofstream(outside) << "precious\n";
  std::string output;
  auto refused = [&](const std::string& out, const std::string& entry, const std::string& why) {
    EXPECT_NE(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
    EXPECT_NE(output.find(out + "/" + entry + " is " + why), std::string::npos) << output;
    EXPECT_FALSE(fs::exists(out + "/results.sqlite")) << "wrote before refusing";
  };
  fs::create_directories(dir + "/a");
  fs::create_symlink(outside, dir + "/a/run.log");
  refused(dir + "/a", "run.log", "a symbolic link");
  fs::create_directories(dir + "/b");
  fs::create_directories(dir + "/elsewhere");
  fs::create_directory_symlink(dir + "/elsewhere", dir + "/b/images");
  refused(dir + "/b", "images", "a symbolic link");
  EXPECT_TRUE(fs::is_empty(dir + "/elsewhere"));
  std::ifstream in(outside);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "precious\n");
  // A finished run whose log was replaced by a FIFO: `report` stops at once, naming it.
  const std::string out = dir + "/c";
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  fs::remove(out + "/run.log");
  ASSERT_EQ(mkfifo((out + "/run.log").c_str(), 0644), 0);
  EXPECT_NE(test::run_cli("report " + out, output), 0) << output;
  EXPECT_NE(output.find(out + "/run.log is not a regular file"), std::string::npos) << output;
}

// Misleading messages and read-only media (hostile input, second round): an edited shard field in
// sweep.json was reported as a --shard option never given; an empty store file as "no such table:
// other.rows"; status, compare and report could not read a run on read-only media.
TEST(Faults, DamagedRecordsAndReadOnlyRunsAreNamedOrRead) {
  const std::string dir = test::scratch_dir("damaged-records");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  // Read-only: the folder and its files lose their write permission (as on read-only media);
  // root writes regardless, so as root the commands run as nobody (setpriv), for whom the
  // folder is read-only.
  fs::permissions(out, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  for (const auto& e : fs::directory_iterator(out))
    fs::permissions(e.path(), fs::perms::owner_write, fs::perm_options::remove);
  // (Where nobody cannot reach the build, e.g. a checkout under /root, the permissions alone.)
  const std::string nobody = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  const bool as_nobody =
      geteuid() == 0 && std::system((nobody + "sh -c 'test -x " + RELIEFLAB_CLI + " && test -r " +
                                     out + "/results.sqlite' 2>/dev/null")
                                        .c_str()) == 0;
  const std::string as = as_nobody ? nobody : "";
  auto read_only = [&](const std::string& args) {
    std::string text;
    EXPECT_EQ(test::run_cli(args, text, as), 0) << args << ": " << text;
    return text;
  };
  EXPECT_NE(read_only("status " + out).find("4 of 4 cells done"), std::string::npos);
  EXPECT_NE(read_only("compare " + out + " " + out).find("4 cells matched"), std::string::npos);
  fs::permissions(out, fs::perms::owner_write, fs::perm_options::add);
  for (const auto& e : fs::directory_iterator(out))
    fs::permissions(e.path(), fs::perms::owner_write, fs::perm_options::add);
  // An empty file as a shard's store.
  const std::string empty = dir + "/empty";
  fs::create_directories(empty);
  fs::copy_file(out + "/sweep.json", empty + "/sweep.json");
  std::ofstream(empty + "/results.sqlite").close();
  EXPECT_NE(test::run_cli("merge " + dir + "/merged " + out + " " + empty, output), 0) << output;
  EXPECT_NE(output.find(empty + "/results.sqlite: not a ReliefLab result store"), std::string::npos)
      << output;
  // An edited shard field.
  std::ifstream in(out + "/sweep.json");
  std::string record((std::istreambuf_iterator<char>(in)), {});
  in.close();
  record.replace(record.find("\"shard\": \"0/1\""), 14, "\"shard\": \"x/y\"");
  std::ofstream(out + "/sweep.json") << record;
  EXPECT_NE(test::run_cli("report " + out, output), 0) << output;
  EXPECT_NE(output.find(out + "/sweep.json: its 'shard' field 'x/y' is not I/N"), std::string::npos)
      << output;
}

// Bytes that are not UTF-8 in run.log (a path in another encoding, a line another tool wrote)
// used to end `report` with a raw JSON exception; the report shows them as U+FFFD.
TEST(Faults, ARunLogInAnotherEncodingStillMakesAReport) {
  const std::string dir = test::scratch_dir("log-encoding");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  std::ofstream(out + "/run.log", std::ios::app) << "latin-1 caf\xe9, broken \xff\xfe\n";
  ASSERT_EQ(test::run_cli("report " + out, output), 0) << output;
  std::ifstream in(out + "/report.html");
  const std::string page((std::istreambuf_iterator<char>(in)), {});
  const std::string replacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8
  EXPECT_NE(page.find("latin-1 caf" + replacement + ", broken " + replacement + replacement),
            std::string::npos);
}

}  // namespace
}  // namespace rl
