// A run folder under commands that overlap, resume and disagree (hostile input, round four):
// two configs run at once into one folder ended with one's sweep.json and the other's rows; a
// shard run into a complete run halved its rows.csv; a merge killed before it wrote sweep.json
// could not be run again; shards that disagreed on a cell were merged without a word; status
// counted a corrupt row as done; and stored values no column can take (a wrong_pct of -5 or
// 1e308) were published, a -1 counted by `compare` as better.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "output/run_folder.h"
#include "support/test_support.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

size_t csv_rows(const std::string& path) {
  std::ifstream in(path);
  size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines ? lines - 1 : 0;
}

// Two different configs at once into one folder: the second waits for the first, and the
// folder ends consistent: the sweep.json of one and the rows.csv of the same one.
TEST(RunFolder, TwoConfigsAtOnceIntoOneFolderEndConsistent) {
  const std::string dir = test::scratch_dir("two-configs");
  const std::string a = test::write_small_sweep(dir + "/a", "images = false\n");
  const std::string b = test::write_small_sweep(dir + "/b", "images = false\nazimuths = [30]\n");
  const std::string out = dir + "/out";
  int codes[2] = {-1, -1};
  std::string outputs[2];
  std::thread first([&] { codes[0] = test::run_cli("run " + a + " --out " + out, outputs[0]); });
  std::thread second([&] { codes[1] = test::run_cli("run " + b + " --out " + out, outputs[1]); });
  first.join();
  second.join();
  EXPECT_EQ(codes[0], 0) << outputs[0];
  EXPECT_EQ(codes[1], 0) << outputs[1];
  const nlohmann::json record = nlohmann::json::parse(read_file(out + "/sweep.json"));
  const std::string last = record["source"].get<std::string>();
  const bool b_last = last == b;
  EXPECT_TRUE(b_last || last == a) << last;
  // rows.csv is the last one's: b's rows say azimuth 30.
  const std::string rows = read_file(out + "/rows.csv");
  EXPECT_EQ(rows.find(",30,") != std::string::npos, b_last) << rows;
  EXPECT_EQ(csv_rows(out + "/rows.csv"), 4u);
}

// A run into a folder another command is writing waits for it, says so, and only then writes.
TEST(RunFolder, ARunWaitsForTheCommandWritingIntoItsFolder) {
  const std::string dir = test::scratch_dir("lock-wait");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out";
  fs::create_directories(out);
  std::string output;
  int code = -1;
  std::thread run;
  {
    const RunFolderLock held(out);  // as a merge or a report writing into it would
    run = std::thread([&] { code = test::run_cli("run " + config + " --out " + out, output); });
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    // The lock is the folder's own: no file in it whose deletion would let the run in.
    for (const auto& e : fs::directory_iterator(out)) fs::remove_all(e.path());
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    EXPECT_FALSE(fs::exists(out + "/sweep.json")) << "the run wrote while the folder was held";
  }
  run.join();
  EXPECT_EQ(code, 0) << output;
  EXPECT_FALSE(fs::exists(out + "/.relieflab-lock")) << "a lock file left behind";
  EXPECT_NE(output.find("waiting for another relieflab command writing into " + out),
            std::string::npos)
      << output;
  EXPECT_EQ(csv_rows(out + "/rows.csv"), 4u);
}

// A shard run into a folder holding the whole run would replace its rows.csv with half of it.
TEST(RunFolder, AShardIntoACompleteRunIsRefusedBeforeAnythingIsWritten) {
  const std::string dir = test::scratch_dir("shard-into-whole");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  const std::string before = read_file(out + "/rows.csv");
  EXPECT_EQ(test::run_cli("run " + config + " --out " + out + " --shard 0/2 -q", output), 2);
  EXPECT_NE(output.find(out + " holds a run of the whole sweep (its sweep.json); this run "
                              "measures shard 0/2"),
            std::string::npos)
      << output;
  EXPECT_EQ(read_file(out + "/rows.csv"), before);
  EXPECT_NE(read_file(out + "/sweep.json").find("\"shard\": \"0/1\""), std::string::npos);
}

// A merge killed after it created its store but before sweep.json (as a Slurm time limit
// would) is resumed by merging again; a store of another sweep's rows is still refused.
TEST(RunFolder, AMergeKilledBeforeItsRecordResumes) {
  const std::string dir = test::scratch_dir("merge-resume");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  std::string output;
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(test::run_cli("run " + config + " --shard " + std::to_string(i) + "/2 --out " + dir +
                                "/s" + std::to_string(i) + " -q",
                            output),
              0)
        << output;
  const std::string merged = dir + "/merged";
  fs::create_directories(merged);
  fs::copy_file(dir + "/s0/results.sqlite", merged + "/results.sqlite");  // half merged
  ASSERT_EQ(test::run_cli("merge " + merged + " " + dir + "/s0 " + dir + "/s1", output), 0)
      << output;
  EXPECT_EQ(csv_rows(merged + "/rows.csv"), 4u);
  // Killed while making its store: an empty file, or an SQLite file with no table yet.
  for (const bool sqlite_header : {false, true}) {
    const std::string cut = dir + (sqlite_header ? "/cut-sqlite" : "/cut-empty");
    fs::create_directories(cut);
    std::ofstream(cut + "/results.sqlite");
    if (sqlite_header) test::store_exec(cut + "/results.sqlite", "PRAGMA user_version = 1");
    ASSERT_EQ(test::run_cli("merge " + cut + " " + dir + "/s0 " + dir + "/s1", output), 0)
        << output;
    EXPECT_EQ(csv_rows(cut + "/rows.csv"), 4u);
  }
  // A store holding a row of a cell this sweep lacks is not a merge of it.
  const std::string other = dir + "/other";
  fs::create_directories(other);
  fs::copy_file(dir + "/s0/results.sqlite", other + "/results.sqlite");
  test::store_exec(other + "/results.sqlite", "UPDATE rows SET key = 'not-a-cell' WHERE rowid = 1");
  EXPECT_EQ(test::run_cli("merge " + other + " " + dir + "/s0 " + dir + "/s1", output), 2);
  EXPECT_NE(output.find("rows of cells this sweep does not have (key not-a-cell)"),
            std::string::npos)
      << output;
  EXPECT_FALSE(fs::exists(other + "/sweep.json"));
}

// Two shards that measured one cell and disagree on it (not on its times) are refused, naming
// the folders, the cell and the column; differing times alone are not a disagreement.
TEST(RunFolder, ShardsThatDisagreeOnACellAreRefusedNamingIt) {
  const std::string dir = test::scratch_dir("merge-disagree");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  std::string output;
  for (const char* name : {"x", "y"})
    ASSERT_EQ(test::run_cli("run " + config + " --out " + dir + "/" + name + " -q", output), 0)
        << output;
  // Times differ between the two runs already; merging them is fine.
  test::store_exec(dir + "/y/results.sqlite",
                   "UPDATE rows SET row = json_set(row, '$.frame_ms', 123.0) WHERE rowid = 1");
  ASSERT_EQ(test::run_cli("merge " + dir + "/m1 " + dir + "/x " + dir + "/y", output), 0) << output;
  test::store_exec(dir + "/y/results.sqlite",
                   "UPDATE rows SET row = json_set(row, '$.wrong_pct', 42.5) WHERE rowid = 2");
  EXPECT_EQ(test::run_cli("merge " + dir + "/m2 " + dir + "/x " + dir + "/y", output), 2);
  EXPECT_NE(output.find(dir + "/x and " + dir + "/y disagree on relief"), std::string::npos)
      << output;
  EXPECT_NE(output.find("'wrong_pct' is "), std::string::npos) << output;
  EXPECT_NE(output.find(" in the other"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(dir + "/m2/rows.csv"));
}

// A value its column cannot take is not published: the run measures the cell again, report
// leaves the row out, status does not count it, and compare refuses the store naming it.
TEST(RunFolder, StoredValuesOutsideTheirColumnsRangeAreNotPublished) {
  const std::string dir = test::scratch_dir("out-of-range");
  const std::string config = test::write_small_sweep(dir, "images = false\n");
  const std::string out = dir + "/out", db = out + "/results.sqlite";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  ASSERT_EQ(test::run_cli("run " + config + " --out " + dir + "/base -q", output), 0) << output;
  test::store_exec(db, "UPDATE rows SET row = json_set(row, '$.wrong_pct', -5) WHERE rowid = 1");
  test::store_exec(db, "UPDATE rows SET row = json_set(row, '$.frame_ms', -1) WHERE rowid = 2");
  test::store_exec(db, "UPDATE rows SET row = json_set(row, '$.wrong_pct', 1e308) WHERE rowid = 3");
  EXPECT_EQ(test::run_cli("status " + out, output), 0) << output;
  EXPECT_NE(output.find("1 of 4 cells done"), std::string::npos) << output;
  EXPECT_NE(output.find("3 stored row(s) cannot stand for their cells"), std::string::npos)
      << output;
  EXPECT_EQ(test::run_cli("report " + out, output), 0) << output;
  EXPECT_NE(output.find("holds a value in 'wrong_pct' its column cannot take: -5 lies outside "
                        "[0, 100] (% of union_px)"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("1e+308 lies outside [0, 100]"), std::string::npos) << output;
  EXPECT_EQ(csv_rows(out + "/rows.csv"), 1u);
  EXPECT_EQ(test::run_cli("compare " + dir + "/base " + out, output), 2);
  EXPECT_NE(output.find("its column cannot take"), std::string::npos) << output;
  // A run measures the three again.
  ASSERT_EQ(test::run_cli("run " + config + " --out " + out + " -q", output), 0) << output;
  EXPECT_NE(output.find("1 already in"), std::string::npos) << output;
  EXPECT_EQ(csv_rows(out + "/rows.csv"), 4u);
}

}  // namespace
}  // namespace rl
