// Table and plot writers: CSV quoting, declared Markdown layouts, Pareto fronts.
#include <gtest/gtest.h>

#include "sweep/pareto.h"
#include "sweep/tables.h"

namespace rl {
namespace {

std::vector<Row> sample_rows() {
  std::vector<Row> rows;
  for (const char* t : {"relief", "parallax"})
    for (int el : {45, 20}) {
      Row r;
      r["technique"] = t;
      r["elevation_deg"] = el;
      r["linear_steps"] = std::string(t) == "relief" ? Row(8) : Row();
      r["artifact_pct"] = el == 45 ? 1.25 : 12.5;
      r["frame_ms"] = 2.0;
      r["note"] = "a,b \"c\"";
      rows.push_back(r);
    }
  return rows;
}

TEST(Csv, QuotesAndOrdersColumns) {
  const std::vector<Row> rows = sample_rows();
  const std::string csv = format_csv(rows, csv_columns(rows, {"technique", "linear_steps"}));
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "technique,linear_steps,elevation_deg,artifact_pct,frame_ms,note");
  EXPECT_NE(csv.find("relief,8,45,1.25,2,\"a,b \"\"c\"\"\""), std::string::npos) << csv;
  EXPECT_NE(csv.find("parallax,,45,"), std::string::npos) << csv;  // no linear_steps: empty
}

TEST(Markdown, LaysOutRowsColumnsAndValues) {
  TableSpec spec;
  spec.rows = {"elevation_deg"};
  spec.columns = {"technique"};
  spec.values = {"artifact_pct", "frame_ms"};
  const std::string md = format_markdown_table(sample_rows(), spec);
  EXPECT_NE(
      md.find("| elevation_deg | technique=relief<br>artifact_pct | technique=relief<br>frame_ms | "
              "technique=parallax<br>artifact_pct | technique=parallax<br>frame_ms |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| 45 | 1.25 | 2 | 1.25 | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 20 | 12.5 | 2 | 12.5 | 2 |"), std::string::npos) << md;
  // Under-specified layouts say so instead of silently dropping rows.
  spec.columns.clear();
  EXPECT_NE(format_markdown_table(sample_rows(), spec).find("2 rows share a table cell"),
            std::string::npos);
}

TEST(Markdown, AggregatesRowsThatShareACell) {
  TableSpec spec;
  spec.columns = {"technique"};
  spec.values = {"artifact_pct", "linear_steps"};
  spec.aggregate = "mean";
  std::string md = format_markdown_table(sample_rows(), spec);
  // relief: mean of 1.25 and 12.5; parallax has no linear_steps anywhere.
  EXPECT_NE(md.find("| 6.875 | 8 | 6.875 | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("mean over the rows that share it (up to 2 per cell)"), std::string::npos);
  spec.aggregate = "max";
  md = format_markdown_table(sample_rows(), spec);
  EXPECT_NE(md.find("| 12.5 | 8 | 12.5 | – |"), std::string::npos) << md;
}

TEST(Pareto, FrontKeepsOnlyUndominatedPoints) {
  std::vector<ParetoPoint> p = {{2, 0.8, "normal", "normal"}, {3, 0.9, "parallax", "parallax"},
                                {10, 0.2, "r8", "relief"},    {20, 0.05, "r32", "relief"},
                                {20, 0.07, "r32b", "relief"}, {40, 0.05, "r64", "relief"},
                                {1, 5.0, "cheap", "x"}};
  const std::vector<size_t> front = pareto_front(p);
  // parallax (dominated by normal), r32b (by r32) and r64 (same error as r32, more cost) drop.
  EXPECT_EQ(front, (std::vector<size_t>{6, 0, 2, 3}));
  const std::string svg = format_svg_plot(p, "t", "fetches_mean", "pos_err_rmse", true);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("r32: fetches_mean=20, pos_err_rmse=0.05"), std::string::npos);
}

}  // namespace
}  // namespace rl
