// The HTML report in a real browser: headless Chromium (Debian's chromium) loads a generated
// report from disk -- no server, no network -- and the rendered DOM must hold every table of
// the config, one plot per (plot, group) whose drawn points equal the rows it shows, and each
// cell's render, truth and error pictures (files that exist). A screenshot is saved.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <set>

#include "core/atomic_write.h"
#include "output/report.h"
#include "support/test_support.h"

namespace rl {
namespace {

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string run_command(const std::string& cmd, int& status) {
  std::string out;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) {
    status = -1;
    return out;
  }
  char buf[4096];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  status = pclose(pipe);
  return out;
}

TEST(Report, ChromiumRendersEveryTablePlotAndPicture) {
  ASSERT_TRUE(std::filesystem::exists(d3_script_path()))
      << d3_script_path() << " missing: run scripts/install-deps.sh (libjs-d3)";
  int status = 0;
  run_command("command -v chromium > /dev/null", status);
  ASSERT_EQ(status, 0) << "chromium missing: run scripts/install-deps.sh";

  const std::string dir = test::scratch_dir("report");
  // The config's text and a table title carry markup that would end or hide the page's data
  // script if embedded as it is (hostile input, second round): the report must render regardless.
  const SweepConfig config = test::run_sweep_in(R"(
# a comment <!--<script> that an HTML parser must never see as markup </script> & more
[sweep]
name = "report_test"
elevations = [45, 20]
azimuths = [30]
viewports = [48]
frames = 1
warmup = 0

[[scene]]
name = "bricks"
relief = { procedural = "bricks", resolution = 64 }
[[scene]]
name = "pyramids"
relief = { procedural = "pyramids", resolution = 64 }

[[technique]]
name = "normal"
[[technique]]
name = "relief"
linear_steps = [8, 32]

[[plot]]
x = "fetches_mean"
y = "wrong_pct"
group = ["scene", "elevation_deg"]
[[plot]]
x = "fetches_mean"
y = "psnr_db"
group = ["scene", "elevation_deg", "technique", "linear_steps"]

[[table]]
file = "a.md"
title = "errors <!--<script>alert(1)</script>"
rows = ["scene", "elevation_deg", "technique", "linear_steps"]
values = ["wrong_pct", "fetches_mean"]
[[table]]
file = "b.tex"
format = "latex"
rows = ["scene", "technique"]
values = ["psnr_db"]
)",
                                                dir);
  const std::string out = dir + "/out";
  const std::string html = out + "/report.html";
  ASSERT_TRUE(std::filesystem::exists(html));
  ASSERT_TRUE(std::filesystem::exists(out + "/report_assets/d3.min.js"));
  ASSERT_TRUE(std::filesystem::exists(out + "/report_assets/report.js"));
  ASSERT_TRUE(std::filesystem::exists(out + "/report_assets/report.css"));
  // The results tree's shared copies are this build's (scripts/reproduce.sh copies them there).
  for (const char* asset : {"report.js", "report.css"})
    EXPECT_EQ(read_text(out + "/report_assets/" + asset),
              read_text(std::string(RELIEFLAB_SOURCE_DIR "/results/report_assets/") + asset))
        << asset << ": results/report_assets/ holds another version; regenerate a folder";
  // One picture taken away, as from a committed reproduction (which keeps no images/): its cell
  // must say so instead of showing a broken image. Done before the one page load that checks
  // everything (each Chromium start is seconds); a tall window puts every lazy picture in view.
  std::string removed;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(out + "/images"))
    if (entry.path().filename().string().ends_with("_render.png")) {
      removed = std::filesystem::relative(entry.path(), out).string();
      break;
    }
  ASSERT_FALSE(removed.empty()) << "no render picture under " << out << "/images";
  ASSERT_TRUE(std::filesystem::remove(out + "/" + removed));
  const std::string dom = run_command(
      "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage "
      "--allow-file-access-from-files --virtual-time-budget=10000 --window-size=1200,40000 "
      "--dump-dom 'file://" +
          html + "' 2> /dev/null",
      status);
  ASSERT_EQ(status, 0);
  ASSERT_NE(dom.find("data-ready=\"1\""), std::string::npos)
      << "the report's script did not finish";
  // 2 scenes x 2 views x 3 settings = 12 cells.
  const size_t cells = 12;
  EXPECT_EQ(count_of(dom, "class=\"rl-table\""), config.tables.size());
  // Each table laid out as its Markdown / LaTeX file: a.md one line per cell; b.tex one line
  // per scene and technique, the first of the rows sharing it shown and a footnote saying so.
  EXPECT_EQ(count_of(dom, "data-rows=\"12\""), 1u);
  EXPECT_EQ(count_of(dom, "data-rows=\"4\""), 1u);
  EXPECT_NE(dom.find("8 rows share a table cell with another row"), std::string::npos);
  // wrong_pct against fetches_mean per scene and view: 4 plots of 3 points; the second plot's
  // 12 groups hold one setting each and are listed, not drawn.
  EXPECT_EQ(count_of(dom, "class=\"rl-plot\""), 4u);
  EXPECT_EQ(count_of(dom, "data-points=\"3\""), 4u);
  EXPECT_EQ(count_of(dom, "class=\"rl-point\""), cells);
  EXPECT_EQ(count_of(dom, "class=\"rl-front\""), 4u);
  EXPECT_NE(dom.find("12 plot group(s) hold a single setting and are not drawn"),
            std::string::npos);
  EXPECT_EQ(count_of(dom, "class=\"rl-series\""), 4u);  // a legend per plot: normal, relief
  EXPECT_EQ(count_of(dom, "\u25cf relief</span>"), 4u);
  EXPECT_EQ(count_of(dom, "class=\"rl-cell\""), cells);
  // Every picture of every cell side by side, pointing at files that exist, but the one taken
  // away: that cell says it is not beside the report.
  std::regex img("<img src=\"([^\"]+)\" alt=\"(render|truth|error)\"");
  size_t images = 0;
  std::set<std::string> kinds;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), img); it != std::sregex_iterator();
       ++it) {
    ++images;
    kinds.insert((*it)[2]);
    EXPECT_TRUE(std::filesystem::exists(out + "/" + (*it)[1].str())) << (*it)[1];
  }
  EXPECT_EQ(images, 3 * cells - 1);
  EXPECT_EQ(kinds.size(), 3u);
  EXPECT_EQ(count_of(dom, "class=\"rl-missing\""), 1u);
  EXPECT_NE(dom.find(removed + " is not beside this report"), std::string::npos) << removed;
  EXPECT_NE(dom.find("id=\"rl-config\""), std::string::npos);
  EXPECT_NE(dom.find("name = \"report_test\""), std::string::npos);  // the config text
  // The markup in the config came through as text, escaped, and ran nothing.
  EXPECT_NE(dom.find("errors &lt;!--&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_EQ(dom.find("<script>alert(1)"), std::string::npos);
  // A screenshot of the rendered page.
  const std::string shot = dir + "/report.png";
  run_command(
      "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage "
      "--allow-file-access-from-files --virtual-time-budget=10000 --window-size=1200,1600 "
      "--screenshot='" +
          shot + "' 'file://" + html + "' > /dev/null 2>&1",
      status);
  ASSERT_TRUE(std::filesystem::exists(shot));
  EXPECT_GT(std::filesystem::file_size(shot), 20000u);
  // relieflab report rebuilds it from the folder alone.
  std::filesystem::remove(html);
  std::string cli;
  EXPECT_EQ(test::run_cli("report " + out, cli), 0) << cli;
  EXPECT_NE(cli.find("from 12 stored rows"), std::string::npos) << cli;
  EXPECT_TRUE(std::filesystem::exists(html));
}

}  // namespace
}  // namespace rl
