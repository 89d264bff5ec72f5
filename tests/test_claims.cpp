// Claims as data (claims/claims.h): rows.csv read back, values and checks evaluated, the README's
// verdict section generated and verified, and malformed claims refused with file and line.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "claims/claims.h"
#include "claims/ledger.h"
#include "config/config.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "output/compare.h"
#include "output/outputs_record.h"
#include "output/rows_csv.h"
#include "output/tables.h"
#include "support/test_support.h"

namespace rl {
namespace {

const char* kRows =
    "technique,scene,elevation_deg,fetches_mean,wrong_pct,note\n"
    "relief,panel,45,30.5,2.5,\"a, \"\"quoted\"\"\n note\"\n"
    "relief,panel,20,40,4.0,\n"
    "relief_exact,panel,45,10,0.5,\n"
    "relief_exact,panel,20,20,0.25,\n";

const char* kClaims = R"(
[[claim]]
id = "exact-cheaper"
judges = "Table 1: the exact search costs less"
verdict = "confirmed"
text = "relief takes {ratio}x the exact search's fetches at 45 degrees ({relief} against {exact})."
[claim.values]
relief = { where = "technique=relief elevation_deg=45.0", column = "fetches_mean" }
exact = { where = "technique=relief_exact elevation_deg=45", column = "fetches_mean" }
ratio = { ratio = ["relief", "exact"], digits = 2 }
[[claim.check]]
that = "ratio > 2"
[[claim.check]]
that = "exact between 5 and 15"

[[claim]]
id = "grazing-worse"
judges = "Section 5: error grows at grazing angles"
verdict = "partly confirmed"
text = "The mean wrong % over both techniques grows from {steep} to {grazing}."
[claim.values]
steep = { where = "elevation_deg=45", column = "wrong_pct", of = "mean" }
grazing = { where = "elevation_deg=20", column = "wrong_pct", of = "mean" }
worst = { max_of = ["steep", "grazing"] }
per_view = { per_row_ratio = ["technique=relief", "technique=relief_exact"], match = ["elevation_deg"], where = "scene=panel|tiles", column = "fetches_mean", of = "min" }
best = { min_of = ["steep", "grazing", "5"] }
[[claim.check]]
that = "grazing > steep"
[[claim.check]]
that = "worst == grazing"
[[claim.check]]
that = "best == steep"
[[claim.check]]
that = "per_view between 1.5 and 2"
)";

std::string write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

// rows.csv as a run writes it: with its digest in outputs.json (output/outputs_record.h).
void write_rows(const std::string& dir, const std::string& rows) {
  std::filesystem::create_directories(dir);
  write(dir + "/rows.csv", rows);
  write_outputs_record(dir, {{"rows.csv", rows}});
}

std::string folder_with(const std::string& name, const std::string& rows, const std::string& claims,
                        const std::string& readme) {
  const std::string dir = test::scratch_dir(name);
  std::filesystem::create_directories(dir);
  write_rows(dir, rows);
  write(dir + "/claims.toml", claims);
  write(dir + "/README.md", readme);
  return dir;
}

// The claims of a folder checked against its rows.
std::vector<ClaimResult> checked(const std::string& dir) {
  return check_claims(load_claims(dir + "/claims.toml"), read_rows_csv(dir + "/rows.csv"));
}

TEST(RowsCsv, ReadsQuotedCellsAndRefusesRaggedRows) {
  const std::vector<CsvRow> rows = parse_rows_csv(kRows, "rows.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].at("note"), "a, \"quoted\"\n note");
  EXPECT_EQ(rows[1].at("note"), "");
  EXPECT_EQ(rows[3].at("wrong_pct"), "0.25");
  try {
    parse_rows_csv("a,b\n1,2\n3\n", "x/rows.csv");
    FAIL() << "a ragged row was read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("x/rows.csv:3: 1 cells, the header has 2"),
              std::string::npos)
        << e.what();
  }
}

// A spreadsheet's byte-order mark is not part of the first column's name; a header naming a
// column twice (a plugin parameter named like a result column) is refused, not half-read.
TEST(RowsCsv, ReadsPastAByteOrderMarkAndRefusesAColumnNamedTwice) {
  const std::vector<CsvRow> rows =
      parse_rows_csv("\xEF\xBB\xBFtechnique,wrong_pct\nrelief,2\n", "r.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("technique"), "relief");
  try {
    parse_rows_csv("technique,wrong_pct,wrong_pct\nrelief,2,3\n", "x/rows.csv");
    FAIL() << "a header with a column named twice was read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("x/rows.csv:1: two columns are named 'wrong_pct' "
                                         "(columns 2 and 3)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Claims, HoldingClaimsFillTheirSentencesFromTheRows) {
  const std::string dir = folder_with("claims_hold", kRows, kClaims, "");
  const ClaimsFile file = load_claims(dir + "/claims.toml");
  const std::vector<ClaimResult> r = check_claims(file, read_rows_csv(dir + "/rows.csv"));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_TRUE(r[0].holds()) << r[0].failures[0];
  EXPECT_EQ(r[0].sentence,
            "relief takes 3x the exact search's fetches at 45 degrees (30.5 against 10).");
  EXPECT_TRUE(r[1].holds());
  EXPECT_EQ(r[1].sentence, "The mean wrong % over both techniques grows from 1.5 to 2.12.");
}

TEST(Claims, AMovedNumberFailsNamingTheClaimAndWhatWasMeasured) {
  std::string rows = kRows;
  rows.replace(rows.find("relief_exact,panel,45,10,"), 25, "relief_exact,panel,45,20,");
  const std::string dir = folder_with("claims_fail", rows, kClaims, "");
  const std::vector<ClaimResult> r = checked(dir);
  ASSERT_EQ(r[0].failures.size(), 2u);
  EXPECT_EQ(r[0].failures[0], "check 'ratio > 2' does not hold: ratio = 1.525, 2 = 2");
  EXPECT_EQ(r[0].failures[1],
            "check 'exact between 5 and 15' does not hold: exact = 20, 5 = 5, 15 = 15");
  EXPECT_TRUE(r[1].holds());
}

TEST(Claims, AFilterThatPicksSeveralRowsNeedsAnAggregate) {
  std::string claims = kClaims;
  claims.replace(claims.find("technique=relief elevation_deg=45.0"), 35, "technique=relief");
  const std::string dir = folder_with("claims_ambiguous", kRows, claims, "");
  const std::vector<ClaimResult> r = checked(dir);
  ASSERT_FALSE(r[0].holds());
  EXPECT_NE(r[0].failures[0].find("value 'relief': 2 rows where technique=relief"),
            std::string::npos)
      << r[0].failures[0];
}

TEST(Claims, MalformedClaimsAreRefusedWithFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"verdict = \"confirmed\"", "verdict = \"sort of\""},
      {"text = \"relief takes {ratio}x", "text = \"relief takes {ratoi}x"},
      {"that = \"ratio > 2\"", "that = \"ratio is big\""},
      {"ratio = { ratio = [\"relief\", \"exact\"], digits = 2 }",
       "ratio = { ratio = [\"relief\", \"exact\"], digts = 2 }"},
  };
  const std::vector<std::string> expected = {
      "claims.toml:5: claim 'exact-cheaper': verdict 'sort of'", "the text names no value 'ratoi'",
      "check 'ratio is big' is neither", "unknown key 'digts'"};
  for (size_t i = 0; i < cases.size(); ++i) {
    std::string claims = kClaims;
    claims.replace(claims.find(cases[i].first), cases[i].first.size(), cases[i].second);
    const std::string dir = folder_with("claims_bad_" + std::to_string(i), kRows, claims, "");
    try {
      load_claims(dir + "/claims.toml");
      ADD_FAILURE() << "accepted: " << cases[i].second;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expected[i]), std::string::npos) << e.what();
    }
  }
}

// Rows measured on a GPU beside the folder's (gpu-<name>/rows.csv): every claim's checks run on
// them too; one that fails there must say so (not_on, not_on_why), and one that says so must
// fail there. The README's section names the renderers and the exception.
TEST(Claims, AVerdictThatHoldsOnOneRendererOnlySaysWhich) {
  std::string gpu_rows = kRows;
  gpu_rows.replace(gpu_rows.find("relief_exact,panel,45,10,"), 25, "relief_exact,panel,45,20,");
  // No renderer column here: the folder's name stands for the renderer.
  const std::string dir = folder_with("claims_renderers", kRows, kClaims,
                                      std::string(kClaimsBegin) + "\n" + kClaimsEnd + "\n");
  std::filesystem::create_directories(dir + "/gpu-x");
  write_rows(dir + "/gpu-x", gpu_rows);
  std::string report;
  EXPECT_EQ(verify_result_folder(dir, true, report), 1) << report;
  EXPECT_NE(report.find("claim exact-cheaper: does not hold on gpu-x (gpu-x/rows.csv): check "
                        "'ratio > 2' does not hold"),
            std::string::npos)
      << report;
  std::string claims = kClaims;
  claims.replace(claims.find("[claim.values]"), 14,
                 "not_on = [\"gpu-x\"]\nnot_on_why = \"the GPU's exact search reads more.\"\n"
                 "[claim.values]");
  write(dir + "/claims.toml", claims);
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, true, report), 0) << report;
  std::ifstream in(dir + "/README.md");
  const std::string readme((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(readme.find("On gpu-x (`gpu-x/rows.csv`) it does not hold: the GPU's exact search "
                        "reads more."),
            std::string::npos)
      << readme;
  EXPECT_NE(readme.find("also runs on the rows measured on gpu-x"), std::string::npos) << readme;
  // Said, but it holds there after all: the exception is stale.
  write_rows(dir + "/gpu-x", kRows);
  report.clear();
  EXPECT_GE(verify_result_folder(dir, false, report), 1);
  EXPECT_NE(report.find("holds on gpu-x (gpu-x/rows.csv) now: drop it from not_on"),
            std::string::npos)
      << report;
}

TEST(Claims, VerifyChecksTheReadmeSectionAndWriteRegeneratesIt) {
  const std::string readme = std::string("# Result\n\nIntro.\n\n") + kClaimsBegin + "\nstale\n" +
                             kClaimsEnd + "\n\nMore.\n";
  const std::string dir = folder_with("claims_readme", kRows, kClaims, readme);
  std::string report;
  EXPECT_EQ(verify_result_folder(dir, false, report), 1);
  EXPECT_NE(report.find("the verdict section differs"), std::string::npos) << report;
  // Each claim whose sentence moved is named, with what the README says and the rows give.
  EXPECT_NE(report.find("claims.toml:2: claim exact-cheaper: the README has no line for it, "
                        "the rows give '...1. **Table 1"),
            std::string::npos)
      << report;
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, true, report), 0) << report;
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, false, report), 0) << report;
  std::ifstream in(dir + "/README.md");
  const std::string now((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(now.find("1. **Table 1: the exact search costs less** — *confirmed*. relief takes 3x"),
            std::string::npos)
      << now;
  EXPECT_NE(now.find("\n\nMore.\n"), std::string::npos) << "text around the section is kept";
  // The report's verdict panel is filled from the claims, and checked like the README.
  write(dir + "/report.html", std::string("<html><script type=\"application/json\" ") +
                                  "id=\"rl-verdicts\">[]</script></html>");
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, false, report), 1);
  EXPECT_NE(report.find("the verdict panel differs"), std::string::npos) << report;
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, true, report), 0) << report;
  std::ifstream page_in(dir + "/report.html");
  const std::string page((std::istreambuf_iterator<char>(page_in)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("{\"holds\":true,\"judges\":\"Table 1: the exact search costs less\""),
            std::string::npos)
      << page;
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, false, report), 0) << report;
  // Rows edited after the run: verify fails naming the file, and --write rewrites nothing (it
  // would launder them into the README while the tables still showed the run's numbers).
  const std::string moved =
      std::string(kRows).replace(std::string(kRows).find(",40,4.0,"), 8, ",40,0.1,");
  write(dir + "/rows.csv", moved);
  std::string output;
  for (const char* write_flag : {"", "--write "}) {
    EXPECT_EQ(test::run_cli(std::string("verify ") + write_flag + dir, output), 1) << output;
    EXPECT_NE(output.find(dir + "/rows.csv: differs from what the run wrote (outputs.json)"),
              std::string::npos)
        << output;
  }
  std::ifstream after_in(dir + "/README.md");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(after_in)), {}), now)
      << "verify --write rewrote the README from edited rows";
  // A run whose rows moved (its own record beside them) fails in the CLI, naming the claim.
  write_rows(dir, moved);
  EXPECT_EQ(test::run_cli("verify " + dir, output), 1) << output;
  EXPECT_NE(output.find("claim grazing-worse: check 'grazing > steep' does not hold"),
            std::string::npos)
      << output;
}

// What verify reads is what a run wrote: a record that leaves rows.csv out, a link standing in
// for the record or the rows, a value its column cannot take (recorded as if a run wrote it),
// and a report edited after the run are refused; the verdict panel verify --write fills is not
// an edit.
TEST(Claims, VerifyRefusesRecordsAndRowsARunDidNotWrite) {
  const std::string readme = std::string("# R\n\n") + kClaimsBegin + "\n" + kClaimsEnd + "\n";
  const std::string dir = folder_with("claims_tamper", kRows, kClaims, readme);
  std::string report;
  ASSERT_EQ(verify_result_folder(dir, true, report), 0) << report;
  auto refused = [&](const std::string& expect) {
    report.clear();
    EXPECT_GT(verify_result_folder(dir, false, report), 0);
    EXPECT_NE(report.find(expect), std::string::npos) << report;
  };
  write_outputs_record(dir, {{"README.md", readme}});
  refused("does not list rows.csv, whose rows the verdicts read");
  const std::string other = folder_with("claims_tamper_other", kRows, kClaims, readme);
  std::filesystem::remove(dir + "/outputs.json");
  std::filesystem::create_symlink(other + "/outputs.json", dir + "/outputs.json");
  refused("outputs.json: a link, not the record this folder's run wrote");
  std::filesystem::remove(dir + "/outputs.json");
  std::filesystem::remove(dir + "/rows.csv");
  std::filesystem::create_symlink(other + "/rows.csv", dir + "/rows.csv");
  write_outputs_record(dir, {{"rows.csv", kRows}});
  refused("rows.csv: a link, not the file the run wrote");
  std::filesystem::remove(dir + "/rows.csv");
  const std::string negative =
      std::string(kRows).replace(std::string(kRows).find(",40,4.0,"), 8, ",40,-50,");
  write_rows(dir, negative);
  refused("rows.csv: row 2: 'wrong_pct' holds -50, a value its column cannot take");
  // The report as the run wrote it, then its panel filled by verify --write: still as written.
  write_rows(dir, kRows);
  const std::string page =
      "<html><script type=\"application/json\" id=\"rl-verdicts\">null</script>"
      "<script src=\"report_assets/report.js\"></script>wrong 2.5</html>";
  write(dir + "/report.html", page);
  write_outputs_record(dir, {{"rows.csv", kRows}, {"report.html", page}});
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, true, report), 0) << report;
  std::string shared = read_text(dir + "/report.html");
  shared.replace(shared.find("\"report_assets/"), 15, "\"../report_assets/");
  write(dir + "/report.html", shared);  // as scripts/reproduce.sh points it at the shared copy
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, false, report), 0) << report;
  std::string edited = shared;
  edited.replace(edited.find("wrong 2.5"), 9, "wrong 0.5");
  write(dir + "/report.html", edited);
  refused("report.html: differs from what the run wrote");
  // A folder holding no claims verifies nothing: that is no pass.
  const std::string empty = test::scratch_dir("claims_none");
  std::filesystem::create_directories(empty);
  std::string output;
  EXPECT_EQ(test::run_cli("verify " + empty, output), 1) << output;
  EXPECT_NE(output.find("nothing was verified"), std::string::npos) << output;
}

// The tables follow from rows.csv: rows edited under them, and their digest recomputed (any tool
// can compute an FNV-1a digest), still disagree with the table the run laid out, which verify
// lays out again from the folder's config. rows.csv read back keeps a key of digits as text.
TEST(Claims, VerifyLaysTheTablesOutAgainFromTheRows) {
  const std::string readme = std::string("# R\n\n") + kClaimsBegin + "\n" + kClaimsEnd + "\n";
  const std::string dir = folder_with("claims_tables", kRows, kClaims, readme);
  write(dir + "/config.toml", R"([sweep]
name = "tables"
elevations = [45, 20]
viewports = [16]
[[scene]]
name = "panel"
relief = { procedural = "sines", resolution = 8 }
[[technique]]
name = "relief"
[[table]]
rows = ["technique"]
columns = ["elevation_deg"]
values = ["wrong_pct", "fetches_mean"]
)");
  const TableSpec spec = load_sweep_config(dir + "/config.toml").tables.at(0);
  auto write_run = [&](const std::string& rows) {
    const std::string table = format_table_file(rows_as_values(parse_rows_csv(rows, "rows")), spec);
    write(dir + "/rows.csv", rows);
    write(dir + "/" + spec.file, table);
    write_outputs_record(dir, {{"rows.csv", rows}, {spec.file, table}});
  };
  write_run(kRows);
  std::string report;
  ASSERT_EQ(verify_result_folder(dir, true, report), 0) << report;
  std::string edited = kRows;
  edited.replace(edited.find(",40,4.0,"), 8, ",40,0.4,");
  write(dir + "/rows.csv", edited);
  write_outputs_record(dir, {{"rows.csv", edited}, {spec.file, read_text(dir + "/" + spec.file)}});
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, false, report), 1) << report;
  EXPECT_NE(report.find(spec.file + ": does not follow from rows.csv"), std::string::npos)
      << report;
  EXPECT_NE(report.find("| relief | 2.5 | 30.5 | 4 | 40 |"), std::string::npos) << report;
  write(dir + "/config.toml", "[sweep]\nname = 3\n");
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, false, report), 1) << report;
  EXPECT_NE(report.find("no longer loads"), std::string::npos) << report;
  const std::vector<Row> typed = rows_as_values(parse_rows_csv(
      "key,wrong_pct,truth_flagged,texture_res\n5715578093281401,nan,true,256\n", "r"));
  EXPECT_TRUE(typed[0]["key"].is_string());
  EXPECT_TRUE(std::isnan(typed[0]["wrong_pct"].get<double>()));
  EXPECT_TRUE(typed[0]["truth_flagged"].get<bool>());
  EXPECT_TRUE(typed[0]["texture_res"].is_number_integer());
}

// A claim about pictures names the rows it describes; the README links their committed files or
// gives the command that makes them, and a claim that speaks of pictures without naming them, or
// names uncommitted ones without a command, fails.
TEST(Claims, ClaimsAboutPicturesNameThemAndTheirFilesOrCommand) {
  const std::string rows =
      "technique,scene,elevation_deg,wrong_pct,image_render,image_truth,image_error\n"
      "relief,panel,45,2.5,images/r.png,images/t.png,images/e.png\n"
      "relief,panel,20,4.0,images/r20.png,images/t20.png,images/e20.png\n";
  auto claims = [](const std::string& extra) {
    return "[[claim]]\nid = \"bands\"\njudges = \"Fig. 3\"\nverdict = \"measured\"\n"
           "text = \"The heat map shows bands; {w}% wrong.\"\n" +
           extra +
           "[claim.values]\nw = { where = \"elevation_deg=45\", column = \"wrong_pct\" }\n"
           "[[claim.check]]\nthat = \"w < 3\"\n";
  };
  const std::string readme = std::string(kClaimsBegin) + "\n" + kClaimsEnd + "\n";
  std::string report;
  // Speaks of a heat map, names none.
  const std::string unnamed = folder_with("claims_pictures_unnamed", rows, claims(""), readme);
  EXPECT_GE(verify_result_folder(unnamed, true, report), 1);
  EXPECT_NE(report.find("claim bands: the text speaks of pictures but names none"),
            std::string::npos)
      << report;
  // A paper's figure named by its number is a reference, not a picture; "the figure" is.
  EXPECT_FALSE(describes_pictures("as in Figure 5.4 and Figures 12 and 13, 3% wrong"));
  EXPECT_TRUE(describes_pictures("the figure shows bands"));
  // Names them, not committed, no command.
  report.clear();
  const std::string nocommand = folder_with("claims_pictures_nocommand", rows,
                                            claims("pictures = \"elevation_deg=45\"\n"), readme);
  EXPECT_EQ(verify_result_folder(nocommand, true, report), 1);
  EXPECT_NE(report.find("are not in the folder and it names no 'pictures_command'"),
            std::string::npos)
      << report;
  // A filter that picks no row.
  report.clear();
  const std::string none = folder_with(
      "claims_pictures_none", rows,
      claims("pictures = \"elevation_deg=5\"\npictures_command = \"make it\"\n"), readme);
  EXPECT_EQ(verify_result_folder(none, true, report), 1);
  EXPECT_NE(report.find("pictures: no row where elevation_deg=5"), std::string::npos) << report;
  // Not committed, with a command: the README gives the command.
  report.clear();
  const std::string dir = folder_with(
      "claims_pictures", rows,
      claims("pictures = \"elevation_deg=45\"\npictures_command = \"scripts/make.sh\"\n"), readme);
  EXPECT_EQ(verify_result_folder(dir, true, report), 0) << report;
  EXPECT_NE(read_text(dir + "/README.md").find("Pictures: `scripts/make.sh`."), std::string::npos);
  // Committed: the README links the row's render, truth and heat map.
  std::filesystem::create_directories(dir + "/images");
  for (const char* f : {"r", "t", "e"}) write(dir + "/images/" + f + ".png", "png");
  report.clear();
  EXPECT_EQ(verify_result_folder(dir, true, report), 0) << report;
  EXPECT_NE(read_text(dir + "/README.md")
                .find("Pictures: panel relief 45° [render](images/r.png) · [truth](images/t.png) · "
                      "[heat map](images/e.png)."),
            std::string::npos)
      << read_text(dir + "/README.md");
}

// The coverage ledger (claims/ledger.h): statuses come from the claims that list an item, and
// every inconsistency is named with its file and line.
const char* kPapers = R"(
[[paper]]
id = "p"
cite = "A paper"
[[paper.item]]
id = "table1"
what = "Table 1"
[[paper.item]]
id = "fig2"
what = "Figure 2"
gap = "only one view"
[[paper.item]]
id = "fig3"
what = "Figure 3"
gap = "no scene for it"
[[paper.item]]
id = "fps"
what = "Absolute frame rates"
not_reproducible = "a 2006 GPU"
instead = "fetches per pixel"
)";

std::string results_with(const std::string& name, const std::string& papers,
                         const std::string& items) {
  const std::string results = test::scratch_dir(name);
  std::filesystem::create_directories(results + "/one");
  write(results + "/papers.toml", papers);
  std::string claims = kClaims;
  claims.insert(claims.find("verdict = "), items + "\n");
  write(results + "/one/claims.toml", claims);
  write(results + "/README.md", std::string("# R\n\n") + kLedgerBegin + "\n" + kLedgerEnd + "\n");
  return results;
}

// The peers re-judgement's acceptance test, on every committed folder: scale the error and cost
// columns that `compare` watches (and the frame and precompute times) by 1.5 and by 1 / 1.5, and
// verify must fail, naming a claim whose sentence or check the change moved. The checks alone,
// without the sentence, catch fewer (relative claims - ratios of one column - are scale-free):
// their count is pinned from below so that claims do not drift back to ratios only.
TEST(Claims, ScaledCommittedRowsFailVerifyNamingTheClaims) {
  std::vector<std::string> columns = {"frame_ms", "frame_ms_min", "precompute_ms"};
  for (const auto& [name, tolerance] : default_tolerances()) columns.push_back(name);
  int folders = 0;
  for (const double factor : {1.5, 1 / 1.5}) {
    int caught = 0, caught_by_checks = 0;
    folders = 0;
    for (const auto& entry : std::filesystem::directory_iterator(RELIEFLAB_SOURCE_DIR "/results")) {
      const std::string dir = entry.path().string();
      if (!std::filesystem::exists(dir + "/claims.toml")) continue;
      ++folders;
      const ClaimsFile file = load_claims(dir + "/claims.toml");
      const std::vector<CsvRow> committed_rows = read_rows_csv(dir + "/rows.csv");
      std::vector<CsvRow> rows = committed_rows;
      for (CsvRow& row : rows)
        for (const std::string& c : columns) {
          auto cell = row.find(c);
          double v = 0;
          char scaled[32];
          if (cell != row.end() && parse_number(cell->second, v)) {
            std::snprintf(scaled, sizeof scaled, "%.17g", v * factor);
            cell->second = scaled;
          }
        }
      const std::vector<ClaimResult> results = check_claims(file, rows);
      std::vector<std::string> named;
      for (const ClaimResult& r : results)
        if (!r.holds()) named.push_back(r.id);
      caught_by_checks += !named.empty();
      // verify also compares each sentence with the README's, which is the committed rows' own
      // (Claims.CommittedResultsHoldTheirVerdicts): a sentence the scaling moved fails there.
      const std::vector<ClaimResult> committed = check_claims(file, committed_rows);
      for (size_t i = 0; i < results.size(); ++i)
        if (results[i].sentence != committed[i].sentence) named.push_back(results[i].id);
      caught += !named.empty();
    }
    EXPECT_GE(caught, folders - 2)
        << "scaled by " << factor << ": " << caught << " of " << folders << " folders fail verify";
    EXPECT_GE(caught_by_checks, 12)
        << "scaled by " << factor << ": only " << caught_by_checks << " folders fail a check";
  }
  EXPECT_GE(folders, 40);
}

TEST(Ledger, StatusesComeFromTheClaimsThatListAnItem) {
  const std::string results = results_with("ledger_ok", kPapers, R"(items = ["p/table1"]
partly = ["p/fig2", "p/fps"])");
  const Ledger ledger = build_ledger(results);
  ASSERT_TRUE(ledger.problems.empty()) << ledger.problems.front();
  ASSERT_EQ(ledger.rows.size(), 4u);
  const std::vector<std::string> want = {"reproduced", "partial", "missing", "not_reproducible"};
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(ledger.rows[i].status, want[i]) << i;
  EXPECT_EQ(ledger.rows[0].claims, std::vector<std::string>{"one/exact-cheaper"});
  EXPECT_EQ(
      ledger_csv(ledger).rfind("paper,item,status,outcome,folder,claims,partly_claims,what,note\n"
                               "p,table1,reproduced,confirmed,one,one/exact-cheaper,,Table 1,\n",
                               0),
      0u)
      << ledger_csv(ledger);
  EXPECT_NE(ledger_totals_markdown(ledger).find("| p | 4 | 1 | 1 | 1 | 1 |"), std::string::npos)
      << ledger_totals_markdown(ledger);
  // Outcomes: confirmed (in full, confirmed), partly confirmed (only in part), missing, and
  // not reproducible here.
  EXPECT_NE(ledger_totals_markdown(ledger).find("| p | 4 | 1 | 1 | 0 | 0 | 1 | 1 |"),
            std::string::npos)
      << ledger_totals_markdown(ledger);
  // Written once, then checked clean; a claim that stops listing an item makes it stale.
  std::string report;
  EXPECT_EQ(ledger_command(results, results + "/README.md", false, report), 3) << report;
  report.clear();
  EXPECT_EQ(ledger_command(results, results + "/README.md", true, report), 0) << report;
  report.clear();
  EXPECT_EQ(ledger_command(results, results + "/README.md", false, report), 0) << report;
  EXPECT_NE(read_text(results + "/README.md").find("| **all** | 4 | 1 | 1 | 1 | 1 |"),
            std::string::npos);
  const std::string claims = read_text(results + "/one/claims.toml");
  write(results + "/one/claims.toml",
        std::string(claims).replace(claims.find("items = [\"p/table1\"]"), 20, ""));
  report.clear();
  EXPECT_EQ(ledger_command(results, results + "/README.md", false, report), 1) << report;
  EXPECT_NE(report.find("papers.toml:5: item p/table1: missing, and says nothing of why"),
            std::string::npos)
      << report;
}

// An item's outcome follows from its claims' verdicts, not from their being there: a claim
// listing it that refutes it makes it contradicted (named), one that only measures, not judged.
TEST(Ledger, OutcomesFollowTheVerdictsOfTheClaims) {
  auto outcome_of_table1 = [](const std::string& name, const std::string& verdict) {
    const std::string results = results_with(name, kPapers, R"(items = ["p/table1"])");
    const std::string claims = read_text(results + "/one/claims.toml");
    write(results + "/one/claims.toml",
          std::string(claims).replace(claims.find("verdict = \"confirmed\""), 21,
                                      "verdict = \"" + verdict + "\""));
    const Ledger ledger = build_ledger(results);
    EXPECT_TRUE(ledger.problems.empty());
    return ledger.rows[0];
  };
  const LedgerRow refuted = outcome_of_table1("ledger_refuted", "refuted");
  EXPECT_EQ(refuted.status, "reproduced");
  EXPECT_EQ(refuted.outcome, "contradicted");
  EXPECT_EQ(refuted.evidence, "one/exact-cheaper (refuted)");
  EXPECT_EQ(outcome_of_table1("ledger_not_confirmed", "not confirmed").outcome, "contradicted");
  EXPECT_EQ(outcome_of_table1("ledger_measured", "measured").outcome, "not judged");
  EXPECT_EQ(outcome_of_table1("ledger_partly", "partly confirmed").outcome, "partly confirmed");
  // The note names the evidence.
  const LedgerRow r = outcome_of_table1("ledger_contradicted_csv", "refuted");
  Ledger one;
  one.papers = {{"p", "A paper"}};
  one.rows = {r};
  EXPECT_NE(ledger_csv(one).find("p,table1,reproduced,contradicted,one,one/exact-cheaper,,Table "
                                 "1,Contradicted by one/exact-cheaper (refuted).\n"),
            std::string::npos)
      << ledger_csv(one);
}

TEST(Ledger, InconsistenciesAreNamed) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"(items = ["p/table1", "p/table9"])", "claim exact-cheaper: no item 'p/table9'"},
      {R"(items = ["p/table1", "p/fig2"])",
       "item p/fig2: reproduced by one/exact-cheaper, but "
       "still says what is missing"},
      {R"(items = ["p/table1", "p/fps"])", "item p/fps: cannot be reproduced here, yet"}};
  for (size_t i = 0; i < cases.size(); ++i) {
    const Ledger ledger =
        build_ledger(results_with("ledger_bad" + std::to_string(i), kPapers, cases[i].first));
    ASSERT_EQ(ledger.problems.size(), 1u) << cases[i].first;
    EXPECT_NE(ledger.problems[0].find(cases[i].second), std::string::npos) << ledger.problems[0];
  }
  std::string papers = kPapers;
  papers.replace(papers.find("instead = \"fetches per pixel\""), 29, "");
  try {
    build_ledger(results_with("ledger_bad_papers", papers, ""));
    ADD_FAILURE() << "accepted not_reproducible without instead";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("papers.toml:16: item 'fps': 'not_reproducible' needs"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rl
