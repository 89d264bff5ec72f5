#include "output/pareto.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "metrics/metrics.h"
#include "output/tables.h"

namespace rl {
namespace {

const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                          "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string safe_file_part(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  return s;
}

}  // namespace

std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<size_t> front;
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].flagged) continue;
    bool dominated = false;
    for (size_t j = 0; j < points.size() && !dominated; ++j) {
      if (i == j || points[j].flagged) continue;
      const ParetoPoint &a = points[j], &b = points[i];
      dominated = a.x <= b.x && a.y <= b.y && (a.x < b.x || a.y < b.y);
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) {
    return points[a].x < points[b].x || (points[a].x == points[b].x && points[a].y < points[b].y);
  });
  return front;
}

namespace {

// The plot's canvas and where a point lands on it: the data's range (x from 0, y padded by 5%,
// on a log axis where asked and some error is positive; zero errors then sit on its floor).
struct PlotFrame {
  static constexpr double W = 900, H = 480, left = 70, right = 330, top = 40, bottom = 50;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  bool use_log = false;
  double floor_y = 0;

  PlotFrame(const std::vector<ParetoPoint>& points, bool log_y) {
    double min_positive = 1e300;
    for (const auto& p : points)
      if (p.y > 0) min_positive = std::min(min_positive, p.y);
    use_log = log_y && min_positive < 1e300;
    floor_y = use_log ? min_positive / 2 : 0;
    bool first = true;
    for (const auto& p : points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      if (first) x0 = x1 = p.x, y0 = y1 = ty(p.y), first = false;
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
      y0 = std::min(y0, ty(p.y)), y1 = std::max(y1, ty(p.y));
    }
    x0 = std::min(x0, 0.0);
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
    const double pad_y = 0.05 * (y1 - y0);
    y0 -= pad_y, y1 += pad_y, x1 += 0.05 * (x1 - x0);
  }
  double ty(double y) const { return use_log ? std::log10(std::max(y, floor_y)) : y; }
  double sx(double x) const { return left + (x - x0) / (x1 - x0) * (W - left - right); }
  double sy(double y) const { return H - bottom - (ty(y) - y0) / (y1 - y0) * (H - top - bottom); }
};

// The axes, their ticks and grid lines, and their names.
std::string svg_axes(const PlotFrame& f, const std::string& x_name, const std::string& y_name) {
  const double W = f.W, H = f.H, left = f.left, right = f.right, top = f.top, bottom = f.bottom;
  std::string s = "<line x1=\"" + fmt(left) + "\" y1=\"" + fmt(H - bottom) + "\" x2=\"" +
                  fmt(W - right) + "\" y2=\"" + fmt(H - bottom) + "\" stroke=\"black\"/>\n";
  s += "<line x1=\"" + fmt(left) + "\" y1=\"" + fmt(top) + "\" x2=\"" + fmt(left) + "\" y2=\"" +
       fmt(H - bottom) + "\" stroke=\"black\"/>\n";
  for (int i = 0; i <= 5; ++i) {
    const double xv = f.x0 + (f.x1 - f.x0) * i / 5, px = f.sx(xv);
    s += "<text x=\"" + fmt(px) + "\" y=\"" + fmt(H - bottom + 15) + "\" text-anchor=\"middle\">" +
         fmt(xv) + "</text>\n";
    const double yv_t = f.y0 + (f.y1 - f.y0) * i / 5;
    const double yv = f.use_log ? std::pow(10.0, yv_t) : yv_t;
    const double py = H - bottom - (yv_t - f.y0) / (f.y1 - f.y0) * (H - top - bottom);
    s += "<text x=\"" + fmt(left - 5) + "\" y=\"" + fmt(py + 4) + "\" text-anchor=\"end\">" +
         fmt(yv) + "</text>\n";
    s += "<line x1=\"" + fmt(left) + "\" y1=\"" + fmt(py) + "\" x2=\"" + fmt(W - right) +
         "\" y2=\"" + fmt(py) + "\" stroke=\"#eee\"/>\n";
  }
  s += "<text x=\"" + fmt((left + W - right) / 2) + "\" y=\"" + fmt(H - 12) +
       "\" text-anchor=\"middle\">" + escape(x_name) + " (cost)</text>\n";
  s += "<text transform=\"translate(16," + fmt((top + H - bottom) / 2) +
       ") rotate(-90)\" text-anchor=\"middle\">" + escape(y_name) +
       (f.use_log ? " (error, log)" : " (error)") + "</text>\n";
  return s;
}

// The Pareto front as a dashed path, then every point in its series' colour (outlined on the
// front, hollow where its truth was not accurate enough to rank it) with its label.
std::string svg_points(const std::vector<ParetoPoint>& points, const PlotFrame& f,
                       const std::map<std::string, int>& colour, const std::string& x_name,
                       const std::string& y_name) {
  const std::vector<size_t> front = pareto_front(points);
  std::string s, path;
  for (size_t i : front)
    path += (path.empty() ? "M" : " L") + fmt(f.sx(points[i].x)) + " " + fmt(f.sy(points[i].y));
  if (!path.empty())
    s += "<path d=\"" + path + "\" fill=\"none\" stroke=\"#555\" stroke-dasharray=\"4 3\"/>\n";
  const std::set<size_t> on_front(front.begin(), front.end());
  for (size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    const char* c = kPalette[colour.at(p.series) % 8];
    const std::string fill = p.flagged ? "none" : c;
    const std::string stroke = on_front.count(i) ? "black" : (p.flagged ? c : "none");
    s += "<circle cx=\"" + fmt(f.sx(p.x)) + "\" cy=\"" + fmt(f.sy(p.y)) + "\" r=\"" +
         (on_front.count(i) ? "5" : "3.5") + "\" fill=\"" + fill + "\" stroke=\"" + stroke +
         "\"><title>" +
         escape(p.label + ": " + x_name + "=" + fmt(p.x) + ", " + y_name + "=" + fmt(p.y)) +
         "</title></circle>\n";
    s += "<text x=\"" + fmt(f.sx(p.x) + 6) + "\" y=\"" + fmt(f.sy(p.y) - 6) +
         "\" font-size=\"9\" fill=\"#333\">" + escape(p.label) + "</text>\n";
  }
  return s;
}

// The series' colours, and what an outlined and a hollow point mean.
std::string svg_legend(const std::vector<ParetoPoint>& points, const PlotFrame& f,
                       const std::map<std::string, int>& colour) {
  const double x = f.W - f.right;
  std::string s;
  double ly = f.top + 10;
  for (const auto& [series, i] : colour) {
    s += "<circle cx=\"" + fmt(x + 20) + "\" cy=\"" + fmt(ly) + "\" r=\"4\" fill=\"" +
         kPalette[i % 8] + "\"/>\n";
    s +=
        "<text x=\"" + fmt(x + 30) + "\" y=\"" + fmt(ly + 4) + "\">" + escape(series) + "</text>\n";
    ly += 16;
  }
  s += "<text x=\"" + fmt(x + 14) + "\" y=\"" + fmt(ly + 10) +
       "\" font-size=\"9\">outlined, dashed: Pareto front</text>\n";
  if (std::any_of(points.begin(), points.end(), [](const ParetoPoint& p) { return p.flagged; }))
    s += "<text x=\"" + fmt(x + 14) + "\" y=\"" + fmt(ly + 24) +
         "\" font-size=\"9\">hollow: truth not accurate enough, not ranked</text>\n";
  return s;
}

}  // namespace

std::string format_svg_plot(const std::vector<ParetoPoint>& points, const std::string& title,
                            const std::string& x_name, const std::string& y_name, bool log_y) {
  const PlotFrame f(points, log_y);
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt(f.W) + "\" height=\"" +
                  fmt(f.H) + "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + fmt(f.W / 2) + "\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">" +
       escape(title) + "</text>\n";
  std::map<std::string, int> colour;  // each series's, numbered in order of first appearance
  for (const auto& p : points) colour.emplace(p.series, int(colour.size()));
  s += svg_axes(f, x_name, y_name);
  s += svg_points(points, f, colour, x_name, y_name);
  s += svg_legend(points, f, colour);
  return s + "</svg>\n";
}

std::vector<PlotGroup> plot_groups(const std::vector<Row>& rows, const PlotSpec& spec,
                                   const std::vector<std::string>& parameter_columns) {
  std::vector<PlotGroup> groups;
  std::map<std::vector<std::string>, size_t> index;
  for (const Row& r : rows) {
    auto x = r.find(spec.x), y = r.find(spec.y);
    if (x == r.end() || y == r.end() || !x->is_number() || !y->is_number()) continue;
    std::vector<std::string> g;
    for (const auto& f : spec.group) g.push_back(r.contains(f) ? format_value(r[f]) : "–");
    auto [it, fresh] = index.emplace(g, groups.size());
    if (fresh) {
      PlotGroup pg;
      pg.values = g;
      for (size_t i = 0; i < g.size(); ++i)
        pg.title += (i ? ", " : "") + spec.group[i] + "=" + g[i];
      groups.push_back(pg);
    }
    ParetoPoint p;
    p.x = x->get<double>();
    p.y = y->get<double>();
    p.series = r.value("technique", "?");
    p.label = p.series;
    for (const auto& c : parameter_columns)
      if (r.contains(c) && !r[c].is_null()) p.label += " " + c + "=" + format_value(r[c]);
    p.key = r.value("key", "");
    p.flagged = (measured_against_truth(spec.x) || measured_against_truth(spec.y)) &&
                r.value("truth_flagged", false);
    if (p.flagged) p.label += std::string(" ") + kTruthFlagMark;
    groups[it->second].points.push_back(p);
  }
  return groups;
}

std::string write_pareto_plots(const std::vector<Row>& rows, const PlotSpec& spec,
                               const std::vector<std::string>& parameter_columns,
                               const std::string& out_dir) {
  std::string md = "### Pareto fronts: " + spec.y + " against " + spec.x + "\n\n";
  md += "Settings no other setting beats on both cost and error, cheapest first.\n\n";
  for (const PlotGroup& g : plot_groups(rows, spec, parameter_columns)) {
    std::string file_part;
    for (size_t i = 0; i < g.values.size(); ++i)
      file_part += (i ? "_" : "") + safe_file_part(g.values[i]);
    const auto& pts = g.points;
    const std::string rel = "plots/" + safe_file_part(spec.y) + "_vs_" + safe_file_part(spec.x) +
                            "__" + file_part + ".svg";
    write_text_atomic(out_dir + "/" + rel,
                      format_svg_plot(pts, g.title, spec.x, spec.y, spec.log_y));
    md += "- **" + g.title + "** ([plot](" + rel + ")): ";
    bool first = true;
    for (size_t i : pareto_front(pts)) {
      md += std::string(first ? "" : " → ") + pts[i].label + " (" + fmt(pts[i].x) + ", " +
            fmt(pts[i].y) + ")";
      first = false;
    }
    long flagged = 0;
    for (const ParetoPoint& p : pts) flagged += p.flagged;
    if (flagged)
      md += " (" + std::to_string(flagged) + " settings not ranked: " + kTruthFlagMark + ")";
    md += "\n";
  }
  return md;
}

}  // namespace rl
