(function () {
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
