#pragma once
// The columns a row may hold, declared by the code that writes them: the metrics, the truth,
// the harness's timing, each representation and each technique (TechniqueInfo::columns).
// Tables, plots, `compare` and the stored-row checks take any declared column, and the
// column reference (docs/columns.md) is generated from the declarations (relieflab docs --update),
// so a column added tomorrow is usable and documented the day it is declared.
#include <string>
#include <vector>

namespace rl {

// A measured number; a flag, stored as a JSON boolean; a text (a label, never a table value);
// a column that names the cell (technique, scene, view, sizes; parameters are the technique's).
enum class ColumnKind { Number, Flag, Text, Identity };

// Which way a number is better: tables mark the best of a row, `compare` calls a change worse or
// better. Neither: a size, a count or a setting of the run (no bold, no direction).
enum class Better { Lower, Higher, Neither };

// How far a number may move between two runs before `compare` calls it a change: the larger of
// `abs` and `rel` times the base value. Unset (both 0): `compare` does not watch the column.
struct CompareTolerance {
  double abs = 0, rel = 0;
  bool watched() const { return abs > 0 || rel > 0; }
};

// A column as its producer declares it: everything tables, plots, `compare` and the report need
// to know about it is here, so adding a column is one declaration. The chained setters read as
// the sentence they declare: {"psnr_db", "dB", "..."}.higher_is_better().compared(0.25, 0).
struct ColumnSpec {
  std::string name;     // rows.csv column, e.g. "wrong_pct"
  std::string unit;     // e.g. "% of pixels", "texels", "ms"; "" for a count or a ratio
  std::string meaning;  // one sentence a reader of a table needs
  ColumnKind kind = ColumnKind::Number;
  Better better = Better::Lower;  // errors and costs: lower is better
  CompareTolerance tolerance{};   // what `compare` watches by default
  bool in_report = false;         // among the numbers each cell shows in the HTML report
  // It scores the technique against the truth: empty when neither covers a pixel, unscored
  // (flagged in tables and plots) when the truth is not accurate enough at the view.
  bool scored_against_truth = false;

  ColumnSpec higher_is_better() const {
    return with([](ColumnSpec& c) { c.better = Better::Higher; });
  }
  ColumnSpec neither_better() const {
    return with([](ColumnSpec& c) { c.better = Better::Neither; });
  }
  ColumnSpec compared(double abs, double rel) const {
    return with([&](ColumnSpec& c) { c.tolerance = {abs, rel}; });
  }
  ColumnSpec reported() const {
    return with([](ColumnSpec& c) { c.in_report = true; });
  }
  ColumnSpec scored() const {
    return with([](ColumnSpec& c) { c.scored_against_truth = true; });
  }

 private:
  template <typename F>
  ColumnSpec with(F&& change) const {
    ColumnSpec c = *this;
    change(c);
    return c;
  }
};

struct DeclaredColumn {
  ColumnSpec spec;
  std::string producer;  // e.g. "metrics", "technique depth_slicing"
  double place = 0;      // its order among its producer's columns (a metric's place in a row)
};

// Adds `columns`, among the producer's others in `place` order. A name declared again must keep
// its unit and kind (two techniques may write the same column for the same quantity); otherwise
// std::logic_error names both producers.
void declare_columns(const std::string& producer, const std::vector<ColumnSpec>& columns,
                     double place = 0);

// Every declared column, in the order declared (libraries declare at load, lowest layer first),
// a producer's own columns in the order of their places.
const std::vector<DeclaredColumn>& declared_columns();
const DeclaredColumn* find_column(const std::string& name);
// The declared numbers and flags: what a table, a plot or `compare` may take as a value.
std::vector<std::string> measured_columns();

// The values a number column can take, from its unit: a share of a whole ("% of union_px") lies
// in [0, 100], other percentages are at least 0; a time, a
// count, a size or an error distance is at least 0; a visibility lies in [-1, 1] (biases
// included); an angle in [-180, 180]; a PSNR at most 100 (capped). Others: any finite value.
struct ValueRange {
  double lo, hi;
};
ValueRange column_range(const ColumnSpec& c);
// "" when `value` can be a value of `c`; else why not ("-5 lies outside [0, 100] (% of
// pixels)").
std::string value_outside_range(const ColumnSpec& c, double value);

// Declares at load time: `static const ColumnDeclaration columns("metrics", {...});`. A
// conflict here is a bug in the declaring code: it prints and exits(3), like a technique's.
struct ColumnDeclaration {
  ColumnDeclaration(const std::string& producer, const std::vector<ColumnSpec>& columns);
};

}  // namespace rl
