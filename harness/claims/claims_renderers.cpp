// Claims checked on every renderer a folder has rows of (claims/claims.h): the folder's own
// rows.csv (llvmpipe for most) and gpu-<name>/rows.csv measured on a GPU beside it.
#include <algorithm>
#include <filesystem>

#include "claims/claims.h"
#include "output/rows_csv.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

bool lists(const Claim& c, const std::string& folder) {
  return std::find(c.not_on.begin(), c.not_on.end(), folder) != c.not_on.end();
}

std::string renderer_of(const RendererRows& r) {
  return r.renderer.empty() ? r.folder : r.renderer;
}

}  // namespace

std::vector<RendererRows> other_renderer_rows(const std::string& dir) {
  std::vector<RendererRows> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("gpu-", 0) != 0 || !fs::is_regular_file(entry.path() / "rows.csv")) continue;
    RendererRows r{name, "", read_rows_csv((entry.path() / "rows.csv").string())};
    if (!r.rows.empty() && r.rows.front().count("renderer"))
      r.renderer = r.rows.front().at("renderer");
    out.push_back(std::move(r));
  }
  std::sort(out.begin(), out.end(),
            [](const RendererRows& a, const RendererRows& b) { return a.folder < b.folder; });
  return out;
}

int verify_other_renderers(const ClaimsFile& file, const std::vector<RendererRows>& others,
                           std::string& report) {
  int failures = 0;
  for (const Claim& c : file.claims) {
    for (const std::string& folder : c.not_on)
      if (std::none_of(others.begin(), others.end(),
                       [&](const RendererRows& r) { return r.folder == folder; })) {
        report += c.where + ": claim " + c.id + ": not_on names " + folder +
                  ", which has no rows.csv here\n";
        ++failures;
      }
    for (const RendererRows& r : others) {
      const std::vector<std::string> why = check_failures(c, r.rows);
      if (!why.empty() && !lists(c, r.folder)) {
        report += c.where + ": claim " + c.id + ": does not hold on " + renderer_of(r) + " (" +
                  r.folder + "/rows.csv): " + why.front() + "; say so with not_on = [\"" +
                  r.folder + "\"] and not_on_why, or mend the claim\n";
        ++failures;
      } else if (why.empty() && lists(c, r.folder)) {
        report += c.where + ": claim " + c.id + ": holds on " + renderer_of(r) + " (" + r.folder +
                  "/rows.csv) now: drop it from not_on\n";
        ++failures;
      }
    }
  }
  return failures;
}

std::string renderer_markdown(const Claim& c, const std::vector<RendererRows>& others) {
  std::string md;
  for (const RendererRows& r : others)
    if (lists(c, r.folder))
      md += " On " + renderer_of(r) + " (`" + r.folder +
            "/rows.csv`) it does not hold: " + c.not_on_why;
  return md;
}

std::string renderers_checked_markdown(const std::vector<RendererRows>& others) {
  if (others.empty()) return "";
  std::string md = "\nEvery check above also runs on the rows measured on";
  for (size_t i = 0; i < others.size(); ++i)
    md += std::string(i ? (i + 1 == others.size() ? " and" : ",") : "") + " " +
          renderer_of(others[i]) + " (`" + others[i].folder + "/rows.csv`)";
  return md + ", and holds there unless its verdict says otherwise.\n";
}

}  // namespace rl
