#include "output/report.h"

#include <cstdlib>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "core/atomic_write.h"
#include "core/columns.h"
#include "output/pareto.h"
#include "output/tables.h"

namespace rl {
namespace fs = std::filesystem;

std::string d3_script_path() {
  const char* env = std::getenv("RELIEFLAB_D3");
  return env && *env ? env : "/usr/share/javascript/d3/d3.min.js";
}

namespace {

std::string cell_title(const Row& r, const std::vector<std::string>& parameter_columns) {
  std::string t = r.value("technique", std::string("?"));
  for (const auto& c : parameter_columns)
    if (r.contains(c) && !r[c].is_null()) t += " " + c + "=" + format_value(r[c]);
  t += " | " + r.value("scene", std::string("?")) + " el " +
       format_value(r.value("elevation_deg", nlohmann::ordered_json())) + " az " +
       format_value(r.value("azimuth_deg", nlohmann::ordered_json())) + " " +
       r.value("viewport", std::string());
  return t;
}

// The report's data: tables, plots (points with their front), cells, config and log.
nlohmann::json report_data(const SweepConfig& config, const std::vector<Row>& rows,
                           const std::vector<std::string>& parameter_columns,
                           const std::string& out_dir) {
  nlohmann::json data;
  data["name"] = config.name;
  data["source"] = config.source;
  data["heat_map_scale"] = config.heat_map_scale;
  data["config"] = config.text;
  data["log"] = read_text(out_dir + "/run.log");
  // The tables as their Markdown and LaTeX forms lay them out (aggregates included).
  for (const TableSpec& spec : config.tables) {
    const TableLayout t = lay_out_table(rows, spec);
    nlohmann::json table;
    table["title"] = t.title.empty() ? spec.file : t.title;
    // Each column in plain words, its full key on hover.
    std::vector<std::string> fields = t.row_fields, keys = t.row_fields;
    for (const auto& c : t.value_columns) {
      fields.push_back(c.group.empty() ? c.metric : c.label + " " + c.metric);
      keys.push_back(c.group.empty() ? c.metric : c.group + " " + c.metric);
    }
    table["fields"] = fields;
    table["field_keys"] = keys;
    table["footnote"] = t.footnote;
    table["rows"] = nlohmann::json::array();
    for (const TableLine& line : t.lines) {
      nlohmann::json values = nlohmann::json::array();
      for (const auto& k : line.row_key) values.push_back(k);
      for (const auto& v : line.values) {
        if (!v)
          values.push_back("");  // no row at this row key and column key
        else if (v->is_number())
          values.push_back(v->get<double>());
        else if (v->is_null())
          values.push_back(nullptr);
        else
          values.push_back(format_value(*v));
      }
      // Per value: a truth_flagged row behind it (the table marks it).
      std::vector<bool> flagged(line.row_key.size(), false);
      flagged.insert(flagged.end(), line.flagged.begin(), line.flagged.end());
      table["rows"].push_back(
          {{"cells", line.cell_keys}, {"values", values}, {"flagged", flagged}});
    }
    table["flag_note"] = t.flagged_values ? truth_flag_note() : std::string();
    data["tables"].push_back(table);
  }
  for (const PlotSpec& p : config.plots)
    for (const PlotGroup& g : plot_groups(rows, p, parameter_columns)) {
      std::vector<bool> front(g.points.size(), false);
      for (size_t i : pareto_front(g.points)) front[i] = true;
      nlohmann::json plot = {{"title", g.title},
                             {"x", p.x},
                             {"y", p.y},
                             {"log_y", p.log_y},
                             {"points", nlohmann::json::array()}};
      for (size_t i = 0; i < g.points.size(); ++i) {
        const ParetoPoint& pt = g.points[i];
        plot["points"].push_back({{"x", pt.x},
                                  {"y", pt.y},
                                  {"series", pt.series},
                                  {"label", pt.label},
                                  {"key", pt.key},
                                  {"front", bool(front[i])},
                                  {"flagged", pt.flagged}});
      }
      data["plots"].push_back(plot);
    }
  // The numbers each cell shows: the columns declared for the report (core/columns.h).
  std::vector<std::string> numbers;
  for (const DeclaredColumn& c : declared_columns())
    if (c.spec.in_report) numbers.push_back(c.spec.name);
  data["cells"] = nlohmann::json::array();
  for (const Row& r : rows) {
    nlohmann::json cell = {{"key", r.value("key", std::string())},
                           {"title", cell_title(r, parameter_columns)}};
    for (const char* img : {"image_render", "image_truth", "image_error"})
      if (r.contains(img) && r[img].is_string()) cell["images"][img] = r[img];
    for (const std::string& n : numbers)
      if (r.contains(n) && r[n].is_number()) cell["numbers"][n] = r[n].get<double>();
    if (r.value("truth_flagged", false)) cell["flag"] = truth_flag_note();
    data["cells"].push_back(cell);
  }
  return data;
}

// The page: its data and verdicts inline, its style and script in report_assets/ beside it, one
// copy for every report of a results tree (scripts/reproduce.sh).
const char* kPage = R"HTML(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>ReliefLab report</title>
<link rel="stylesheet" href="report_assets/report.css">
<script src="report_assets/d3.min.js"></script></head>
<body><h1 id="rl-title"></h1><p id="rl-source"></p>
<div id="rl-verdicts-box" hidden><h2>Verdicts</h2><p>Generated from the result folder's claims.toml with the numbers of rows.csv (<code>relieflab verify</code>).</p><ol id="rl-verdicts-list"></ol></div>
<h2>Tables</h2><div id="rl-tables"></div>
<h2>Error against cost</h2><p>Each point is a cell (hover: its setting; click: its pictures); the dashed line is the Pareto front.</p><div id="rl-plots" class="rl-plots"></div>
<h2>Cells</h2><p>Render, truth and error heat map of each cell. Heat map: position error from 0 to <span id="rl-scale"></span> texels, <span style="color:#e0e">magenta</span> missed, <span style="color:#0cc">cyan</span> false hit.</p><div class="rl-legend"></div><div id="rl-cells"></div>
<h2>Config</h2><pre id="rl-config"></pre><h2>run.log</h2><pre id="rl-log"></pre>
<script type="application/json" id="rl-data">@DATA@</script>
<script type="application/json" id="rl-verdicts">[]</script>
<script src="report_assets/report.js"></script></body></html>
)HTML";

const char* kStyle =
    R"CSS(body{font:14px/1.4 sans-serif;margin:1.5em;color:#222}h1{font-size:1.5em}h2{margin-top:1.6em}
table.rl-table{border-collapse:collapse;font-size:12px}table.rl-table td,table.rl-table th{border:1px solid #ccc;padding:2px 6px;text-align:right}
table.rl-table th{cursor:pointer;background:#f3f3f3;position:sticky;top:0}.rl-table-box{max-height:36em;max-width:100%;width:fit-content;overflow:auto;margin-top:4px}.rl-lone{font-size:12px;color:#555}.rl-footnote{font-size:12px;color:#555}.rl-flagged{background:#fff3cd}table.rl-table td:first-child{text-align:left}
.rl-plots{display:flex;flex-wrap:wrap;gap:1em}.rl-plot{border:1px solid #ddd;padding:4px}
.rl-plot .domain{fill:none;stroke:#444}.rl-plot .tick line{stroke:#444}.rl-plot text{font-size:11px}
.rl-series{font-size:11px;max-width:380px}.rl-series span{margin-right:8px;white-space:nowrap}.rl-point{cursor:pointer;stroke:#fff;stroke-width:0.5}.rl-front{fill:none;stroke:#222;stroke-dasharray:4 3}
.rl-cell{border-top:1px solid #ddd;padding-top:.5em}.rl-cell img{width:256px;image-rendering:pixelated;margin-right:6px;border:1px solid #ccc}
.rl-missing{display:inline-block;width:248px;min-height:3em;word-break:break-all;margin-right:6px;padding:4px;border:1px dashed #bbb;color:#777;font-size:11px;vertical-align:top}
.rl-legend{height:12px;width:256px;background:linear-gradient(to right,#30123b,#4686fb,#1be5b5,#a4fc3c,#fbb938,#e4460a,#7a0403)}
pre{background:#f7f7f7;padding:.6em;max-height:24em;overflow:auto;font-size:12px}
)CSS";

const char* kScript = R"JS((function () {
  var data = JSON.parse(document.getElementById('rl-data').textContent);
  var el = function (tag, attrs, text) {
    var e = document.createElement(tag);
    for (var k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    return e;
  };
  var fmt = function (v) { return v === null ? '–' : (typeof v === 'number' ? +v.toPrecision(4) + '' : v); };
  document.getElementById('rl-title').textContent = 'ReliefLab: ' + data.name;
  document.getElementById('rl-source').textContent = 'Config: ' + data.source;
  document.getElementById('rl-scale').textContent = data.heat_map_scale;
  document.getElementById('rl-config').textContent = data.config;
  document.getElementById('rl-log').textContent = data.log;
  var verdicts = JSON.parse(document.getElementById('rl-verdicts').textContent);
  if (verdicts.length) {
    document.getElementById('rl-verdicts-box').hidden = false;
    verdicts.forEach(function (v) {
      var li = el('li', v.holds ? {} : {'class': 'rl-flagged'});
      li.appendChild(el('strong', {}, v.judges));
      li.appendChild(document.createTextNode(' — '));
      li.appendChild(el('em', {}, v.verdict + (v.holds ? '' : ' (no longer holds)')));
      li.appendChild(document.createTextNode('. ' + v.sentence.replace(/[*`]/g, '')));  // Markdown marks
      var items = (v.items || []).concat((v.partly || []).map(function (i) { return i + ' (in part)'; }));
      if (items.length) {  // the paper items it judges, in the coverage ledger beside the folder
        var p = el('p', {}, 'Paper items: ' + items.join(', ') + ' — ');
        p.appendChild(el('a', {href: '../LEDGER.md'}, 'coverage ledger'));
        li.appendChild(p);
      }
      var pics = v.pictures || {rows: [], command: ''};
      if (pics.command) li.appendChild(el('p', {}, 'Pictures: ' + pics.command));
      pics.rows.forEach(function (p) {  // the cells the claim rests on: render, truth, heat map
        var row = el('div', {'class': 'rl-claim-pictures'}, p.label + ' ');
        [p.render, p.truth, p.error].forEach(function (src) {
          var a = el('a', {href: src});
          a.appendChild(el('img', {src: src, width: 128, alt: src}));
          row.appendChild(a);
        });
        li.appendChild(row);
      });
      document.getElementById('rl-verdicts-list').appendChild(li);
    });
  }
  (data.tables || []).forEach(function (t) {
    var box = document.getElementById('rl-tables');
    box.appendChild(el('h3', {}, t.title));
    var filter = el('input', {'class': 'rl-filter', placeholder: 'filter rows'});
    box.appendChild(filter);
    var table = el('table', {'class': 'rl-table', 'data-rows': t.rows.length});
    var head = el('tr');
    var body = el('tbody');
    t.fields.forEach(function (f, i) {
      var th = el('th', {title: (t.field_keys || [])[i] || f}, f);
      th.onclick = function () {
        var rows = Array.prototype.slice.call(body.rows);
        var up = th.getAttribute('data-order') !== 'up';
        th.setAttribute('data-order', up ? 'up' : 'down');
        rows.sort(function (a, b) {
          var x = a.cells[i].getAttribute('data-v'), y = b.cells[i].getAttribute('data-v');
          var nx = parseFloat(x), ny = parseFloat(y);
          var c = (!isNaN(nx) && !isNaN(ny)) ? nx - ny : (x < y ? -1 : x > y ? 1 : 0);
          return up ? c : -c;
        });
        rows.forEach(function (r) { body.appendChild(r); });
      };
      head.appendChild(th);
    });
    var thead = el('thead');
    thead.appendChild(head);
    table.appendChild(thead);
    t.rows.forEach(function (r) {
      var tr = el('tr');
      r.values.forEach(function (v, i) {
        var td = el('td', {'data-v': v === null ? '' : v});
        if (i === 0 && r.cells.length) {
          // A line that combines several cells (an aggregate) links to the first of them.
          var a = el('a', {href: '#cell-' + r.cells[0]}, fmt(v));
          if (r.cells.length > 1) a.setAttribute('title', r.cells.length + ' cells behind this line; the link opens the first');
          td.appendChild(a);
        } else {
          td.textContent = fmt(v);
        }
        if (r.flagged && r.flagged[i]) {
          td.className = 'rl-flagged';
          td.appendChild(document.createTextNode(' \u2691'));
          td.title = 'truth not accurate enough at this view to score it';
        }
        tr.appendChild(td);
      });
      body.appendChild(tr);
    });
    table.appendChild(body);
    filter.oninput = function () {
      var q = filter.value.toLowerCase();
      Array.prototype.forEach.call(body.rows, function (r) {
        r.style.display = r.textContent.toLowerCase().indexOf(q) >= 0 ? '' : 'none';
      });
    };
    // A long table scrolls in its own box (headers stay in view) rather than pushing the plots away.
    var scroller = el('div', {'class': 'rl-table-box'});
    scroller.appendChild(table);
    box.appendChild(scroller);
    if (t.footnote) box.appendChild(el('p', {'class': 'rl-footnote'}, t.footnote));
    if (t.flag_note) box.appendChild(el('p', {'class': 'rl-footnote rl-flag-note'}, t.flag_note));
  });
  if (typeof d3 === 'undefined') {
    document.getElementById('rl-plots').textContent = 'd3 was not found when the report was written (install libjs-d3): no plots.';
  } else {
    var colour = d3.scale.category10();
    // A group with one setting has no trade-off to draw: counted, not plotted (its numbers are
    // in the tables).
    var lone = (data.plots || []).filter(function (p) { return p.points.length < 2; });
    if (lone.length) {
      document.getElementById('rl-plots').parentNode.insertBefore(el('p', {'class': 'rl-lone'},
          lone.length + ' plot group(s) hold a single setting and are not drawn: ' +
          lone.slice(0, 4).map(function (p) { return p.title; }).join('; ') +
          (lone.length > 4 ? '; …' : '')), document.getElementById('rl-plots'));
    }
    (data.plots || []).filter(function (p) { return p.points.length >= 2; }).forEach(function (p) {
      var w = 380, h = 250, m = {l: 56, r: 12, t: 34, b: 40};
      // A flat extent (every setting at one cost) still gets an axis.
      var padded = function (e) { return e[0] === e[1] ? [e[0] - 1, e[1] + 1] : e; };
      var div = el('div', {'class': 'rl-plot', 'data-points': p.points.length});
      document.getElementById('rl-plots').appendChild(div);
      var svg = d3.select(div).append('svg').attr('width', w).attr('height', h);
      svg.append('text').attr('x', 4).attr('y', 12).style('font-weight', 'bold').text(p.title);
      var xs = d3.scale.linear().domain(padded(d3.extent(p.points, function (d) { return d.x; }))).nice().range([m.l, w - m.r]);
      var ylo = d3.min(p.points, function (d) { return d.y > 0 ? d.y : Infinity; });
      var logy = p.log_y && isFinite(ylo);
      var yf = function (d) { return logy ? Math.max(d.y, ylo) : d.y; };
      var ye = d3.extent(p.points, yf);
      if (ye[0] === ye[1]) ye = logy ? [ye[0] / 2, ye[1] * 2] : [ye[0] - 1, ye[1] + 1];
      var ys = (logy ? d3.scale.log() : d3.scale.linear()).domain(ye).nice().range([h - m.b, m.t]);
      svg.append('g').attr('transform', 'translate(0,' + (h - m.b) + ')').call(d3.svg.axis().scale(xs).ticks(5));
      svg.append('g').attr('transform', 'translate(' + m.l + ',0)').call(d3.svg.axis().scale(ys).orient('left').ticks(5, logy ? '.2g' : null));
      svg.append('text').attr('x', w - m.r).attr('y', h - 6).attr('text-anchor', 'end').text(p.x);
      svg.append('text').attr('x', 4).attr('y', m.t - 8).text(p.y);
      var front = p.points.filter(function (d) { return d.front; }).sort(function (a, b) { return a.x - b.x; });
      svg.append('path').attr('class', 'rl-front').attr('d', d3.svg.line().x(function (d) { return xs(d.x); }).y(function (d) { return ys(yf(d)); })(front));
      svg.selectAll('circle').data(p.points).enter().append('circle')
        .attr('class', 'rl-point').attr('r', 4)
        .attr('cx', function (d) { return xs(d.x); }).attr('cy', function (d) { return ys(yf(d)); })
        .attr('fill', function (d) { return d.flagged ? 'none' : colour(d.series); })
        .attr('stroke', function (d) { return d.flagged ? colour(d.series) : null; })
        .on('click', function (d) { location.hash = '#cell-' + d.key; })
        .append('title').text(function (d) { return d.label + '\n' + p.x + ' ' + fmt(d.x) + ', ' + p.y + ' ' + fmt(d.y) + (d.front ? ' (on the front)' : '') + (d.flagged ? ' (truth not accurate enough at this view: not ranked)' : ''); });
      // Which colour is which series (the technique), under the plot.
      var legend = el('div', {'class': 'rl-series'});
      d3.set(p.points.map(function (d) { return d.series; })).values().forEach(function (name) {
        var item = el('span', {}, '\u25cf ' + name);
        item.style.color = colour(name);
        legend.appendChild(item);
      });
      div.appendChild(legend);
    });
  }
  data.cells.forEach(function (c) {
    var s = el('section', {'class': 'rl-cell', id: 'cell-' + c.key});
    s.appendChild(el('h3', {}, c.title));
    ['image_render', 'image_truth', 'image_error'].forEach(function (k) {
      if (!c.images || !c.images[k]) return;
      var what = k.replace('image_', '');
      // Lazy: a 1000-cell sweep's pictures load as they scroll into view.
      var img = el('img', {src: c.images[k], alt: what, title: what, loading: 'lazy'});
      // A report copied without its images/ folder (a committed reproduction) says so.
      img.onerror = function () {
        img.parentNode.replaceChild(el('span', {'class': 'rl-missing'}, what + ': ' + c.images[k] + ' is not beside this report'), img);
      };
      s.appendChild(img);
    });
    var nums = [];
    for (var k in c.numbers || {}) nums.push(k + ' ' + fmt(c.numbers[k]));
    s.appendChild(el('p', {}, nums.join(' · ')));
    if (c.flag) s.appendChild(el('p', {'class': 'rl-flagged'}, c.flag));
    document.getElementById('rl-cells').appendChild(s);
  });
  document.body.setAttribute('data-ready', '1');
})();
)JS";

}  // namespace

namespace {

// JSON for a <script> element: no text from a config (a comment, a title, a name) may change
// the page's structure. "</script>" would end the element and "<!--" followed by "<script"
// would keep the next "</script>" from ending it (the report then shows nothing), so every
// '<', '>' and '&' is written as its JSON unicode escape, which JSON.parse undoes.
std::string script_json(const nlohmann::json& value) {
  std::string out;
  // Bytes that are not UTF-8 (a run.log line naming a file in another encoding) are shown as
  // U+FFFD rather than failing the whole report.
  for (char ch : value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)) {
    if (ch == '<')
      out += "\\u003c";
    else if (ch == '>')
      out += "\\u003e";
    else if (ch == '&')
      out += "\\u0026";
    else
      out += ch;
  }
  return out;
}

const char* const kVerdictsOpen = "<script type=\"application/json\" id=\"rl-verdicts\">";

}  // namespace

bool set_report_verdicts(std::string& page, const nlohmann::json& verdicts) {
  const size_t open = page.find(kVerdictsOpen);
  if (open == std::string::npos) return false;
  const size_t begin = open + std::string(kVerdictsOpen).size();
  const size_t end = page.find("</script>", begin);
  page.replace(begin, end - begin, script_json(verdicts));
  return true;
}

nlohmann::json report_verdicts(const std::string& page) {
  const size_t open = page.find(kVerdictsOpen);
  if (open == std::string::npos) return nullptr;
  const size_t begin = open + std::string(kVerdictsOpen).size();
  return nlohmann::json::parse(page.substr(begin, page.find("</script>", begin) - begin), nullptr,
                               false);
}

bool write_report(const SweepConfig& config, const std::vector<Row>& rows,
                  const std::vector<std::string>& parameter_columns, const std::string& out_dir) {
  const std::string json = script_json(report_data(config, rows, parameter_columns, out_dir));
  std::string page = kPage;
  page.replace(page.find("@DATA@"), 6, json);
  fs::create_directories(out_dir + "/report_assets");
  write_text_atomic(out_dir + "/report_assets/report.css", kStyle);
  write_text_atomic(out_dir + "/report_assets/report.js", kScript);
  bool have_d3 = fs::exists(d3_script_path());
  if (have_d3) write_text_atomic(out_dir + "/report_assets/d3.min.js", read_text(d3_script_path()));
  write_text_atomic(out_dir + "/report.html", page);
  return have_d3;
}

}  // namespace rl
