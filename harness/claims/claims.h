#pragma once
// A reproduction's verdicts as data (results/<name>/claims.toml), checked against its rows.csv
// so that a sentence can never drift from its table.
//
// A claim names the paper statement it judges, its verdict, and a sentence whose {value}s are
// filled in from the rows. Values are read from rows picked by a filter, or derived from other
// values (ratio / difference of two, min_of / max_of several); checks are comparisons that must
// hold for the verdict to stand:
//
//   [[claim]]
//   id = "fetches-fall"
//   judges = "Figure 12: allowing error buys larger safety radii"
//   verdict = "confirmed"
//   text = "Fetches fall {ratio}x on the panel at 45 degrees as error_allowed goes 0 to 0.2."
//   [claim.values]
//   at0 = { where = "scene=panel elevation_deg=45 error_allowed=0", column = "fetches_mean" }
//   at2 = { where = "scene=panel elevation_deg=45 error_allowed=0.2", column = "fetches_mean" }
//   ratio = { ratio = ["at0", "at2"], digits = 2 }
//   [[claim.check]]
//   that = "ratio > 4"
//   pictures = "scene=panel elevation_deg=45"        (if the text speaks of pictures)
//   pictures_command = "scripts/reproduce.sh --images configs/papers/x.toml"
//   items = ["baboud2006/fig12-error-allowed"]       (paper items it reproduces; `partly` = [...]
//                                                      for those it covers in part)
//
// A filter's field=value pairs match a row's cells as numbers when both are numbers, else as
// text (value "a|b" matches either); a value reads exactly one row unless it names an aggregate
// (of = "mean", "min", "max").
// Checks: "A op B" (op one of < <= > >= ==) or "A between B and C", with A, B, C value names or
// numbers. `relieflab verify` checks every claim and that the README's generated verdict
// section (between the kClaimsBegin / kClaimsEnd markers) says what the claims say now.
#include <map>
#include <string>
#include <vector>

#include "output/rows_csv.h"

namespace rl {

struct ClaimValue {
  std::string name;
  // A column read from rows (where / column / of), or derived from other values: the ratio or
  // difference of two, or the least or greatest of several.
  std::string where, column, of;  // of: "" (exactly one row), "mean", "min" or "max"
  std::string derive;             // "", "ratio", "difference", "min_of" or "max_of"
  std::vector<std::string> args;
  // per_row_ratio = [NUMERATOR, DENOMINATOR]: filters; each numerator row (within `where`) is
  // paired with the denominator row that has the same `match` fields, their `column`s divided,
  // and the ratios aggregated by `of` (a paper table's "ML / HF per matching row").
  std::vector<std::string> match;
  int digits = 3;  // significant digits in the sentence
};

struct Claim {
  std::string id, judges, verdict, text;
  std::vector<ClaimValue> values;
  std::vector<std::string> checks;
  // A claim about pictures names the rows whose render, truth and heat map it describes (a
  // filter, as `where`), and the command that makes them where the folder does not commit them.
  // A text that speaks of pictures (describes_pictures) must name them.
  std::string pictures, pictures_command;
  // The paper items it reproduces ("paper/item", as results/papers.toml names them) and those it
  // covers only in part: the coverage ledger's input (claims/ledger.h).
  std::vector<std::string> items, partly;
  // Rows measured on another renderer beside the folder's own (gpu-<name>/rows.csv): the ones
  // this claim's checks do not hold on, and why. verify checks every claim on every such file
  // and fails where one does not hold unlisted, or holds listed (claims/claims_renderers.cpp).
  std::vector<std::string> not_on;
  std::string not_on_why;
  std::string where;  // "claims.toml:LINE", for messages
};

// Does a claim's sentence speak of pictures (heat maps, renders, images, figures, looks)? A
// paper's "Figure 5.4" or "Figures 12 and 13" is a reference, not talk of pictures.
bool describes_pictures(const std::string& text);

struct ClaimsFile {
  std::string path;
  std::vector<Claim> claims;
};

// Throws ConfigError naming file, line and key on a malformed file.
ClaimsFile load_claims(const std::string& path);
// The whitespace-separated words of a check ("A between B and C") or a filter ("k=v k=v").
std::vector<std::string> claim_words(const std::string& text);

// One row's pictures, as rows.csv names them (relative to the result folder).
struct ClaimPicture {
  std::string label, render, truth, error;
};

struct ClaimResult {
  std::string id;
  std::string sentence;                // the text with the measured values filled in
  std::vector<std::string> failures;   // each check that does not hold, or a value not found
  std::vector<ClaimPicture> pictures;  // the rows `pictures` picks
  bool pictures_committed = false;     // every one of their files is in the folder
  bool holds() const { return failures.empty(); }
};
std::vector<ClaimResult> check_claims(const ClaimsFile& file, const std::vector<CsvRow>& rows);
// Why each of the claim's checks does not hold on `rows` (a value not found among them), empty
// when they all hold.
std::vector<std::string> check_failures(const Claim& c, const std::vector<CsvRow>& rows);

// The rows of a folder measured on another renderer: gpu-<name>/rows.csv beside its rows.csv.
struct RendererRows {
  std::string folder;    // "gpu-h200"
  std::string renderer;  // the rows' renderer column, e.g. "NVIDIA H200/PCIe/SSE2"
  std::vector<CsvRow> rows;
};
std::vector<RendererRows> other_renderer_rows(const std::string& dir);
// Each claim checked on each renderer's rows; one report line (and one failure counted) per
// claim that does not hold on one and does not say so in not_on, or says so and holds, or
// names a folder that is not there.
int verify_other_renderers(const ClaimsFile& file, const std::vector<RendererRows>& others,
                           std::string& report);

inline constexpr const char* kClaimsBegin = "<!-- claims: generated from claims.toml -->";
inline constexpr const char* kClaimsEnd = "<!-- claims: end -->";
// The README's verdict section: one numbered item per claim, its pictures linked where the
// folder commits them, else the command that makes them.
// " On NVIDIA H200/... (gpu-h200/rows.csv) it does not hold: <not_on_why>." for each of `others`
// the claim lists in not_on; and the line naming the renderers a folder's claims ran on.
std::string renderer_markdown(const Claim& c, const std::vector<RendererRows>& others);
std::string renderers_checked_markdown(const std::vector<RendererRows>& others);
// With `others`, each claim that does not hold on one says so, and a last line names every
// renderer the checks ran on.
std::string claims_markdown(const ClaimsFile& file, const std::vector<ClaimResult>& results,
                            const std::vector<RendererRows>& others = {});

// Checks each folder's claims.toml against its rows.csv and its README's generated section
// (with `write`, rewrites that section instead of comparing it). Appends a line per failure to
// `report` ("DIR/claims.toml:LINE: claim ID: ..."); returns the number of failures.
int verify_result_folder(const std::string& dir, bool write, std::string& report);

}  // namespace rl
