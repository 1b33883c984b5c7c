#include "experiments/report/report_page_assets.hpp"

namespace rapid {

std::string report_page_css() {
  return R"css(body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; margin: 0 auto; max-width: 1200px; padding: 0 16px 48px; color: #1b1b1b; }
header { border-bottom: 1px solid #ccc; margin-bottom: 8px; }
nav a { margin-right: 12px; }
h2 { margin-top: 32px; border-bottom: 1px solid #eee; }
table { border-collapse: collapse; margin: 8px 0 16px; }
th, td { border: 1px solid #ddd; padding: 3px 8px; vertical-align: top; }
thead th { background: #f4f4f4; }
table.numbers td[data-sort] { text-align: right; font-variant-numeric: tabular-nums; }
table.sortable thead th { cursor: pointer; user-select: none; }
table.sortable thead th::after { content: " \2195"; color: #999; }
table.sortable thead th[aria-sort="ascending"]::after { content: " \25B2"; color: #000; }
table.sortable thead th[aria-sort="descending"]::after { content: " \25BC"; color: #000; }
td.best { font-weight: bold; background: #e3f6fb; }
td.cell a { color: inherit; text-decoration: none; border-bottom: 1px dotted #888; }
table.facts th { text-align: left; background: #f9f9f9; white-space: nowrap; }
#answer { background: #fafcff; border: 1px solid #dde6f0; border-radius: 6px; padding: 4px 14px; margin-top: 16px; }
#answer h2 { margin-top: 8px; }
ul.answer-best { margin: 4px 0 12px; padding-left: 20px; }
.verdict { font-weight: bold; white-space: nowrap; }
.verdict-pass, .verdict-confirmed { color: #176c1a; }
.verdict-fail, .verdict-refuted { color: #b01c1c; }
.verdict-n-a, .verdict-undecided { color: #7a5c00; }
figure { margin: 16px 0; }
img.figure { max-width: 100%; height: auto; border: 1px solid #eee; }
figcaption { color: #444; font-size: 13px; }
details.cell-detail { border: 1px solid #ddd; border-radius: 4px; margin: 4px 0; padding: 2px 8px; }
details.cell-detail[open] { background: #fcfcfc; }
details summary { cursor: pointer; }
svg.seed-curves { font: 10px sans-serif; }
svg.interval-plot, svg.profile { font: 10px sans-serif; }
svg.interval-plot rect.frame, svg.profile rect.frame { fill: none; stroke: #999; }
svg.interval-plot line.interval { stroke-width: 2; }
svg.interval-plot line.reference { stroke: #777; stroke-dasharray: 4 3; }
svg.profile polyline { fill: none; stroke-width: 1.6; }
svg.profile text.title { font-weight: bold; }
figure.profiles svg { margin-right: 8px; }
svg.seed-curves rect.frame { fill: none; stroke: #999; }
svg.seed-dots { font: 10px sans-serif; display: block; }
svg.seed-dots line.axis { stroke: #999; }
svg.seed-dots line.spread { stroke: #444; stroke-width: 4; stroke-opacity: 0.35; }
svg.seed-dots line.mean { stroke: #222; stroke-width: 1.5; }
svg.seed-curves polyline { fill: none; stroke-width: 1.4; }
.swatch { display: inline-block; width: 10px; height: 10px; margin-right: 6px; border-radius: 2px; }
.status-ok { color: #176c1a; }
.status-failed, .status-diverged, .status-corrupt { color: #b01c1c; font-weight: bold; }
.status-missing, .status-stale { color: #7a5c00; font-weight: bold; }
code.absent { color: #777; }
.note, .missing { color: #555; font-style: italic; }
)css";
}

std::string report_page_script() {
  return R"js((function () {
  'use strict';
  // What went wrong while the page ran; #selftest reports it.
  var problems = [];
  window.addEventListener('error', function (e) { problems.push('error: ' + e.message); });
  var consoleError = console.error;
  console.error = function () {
    problems.push('console.error: ' + Array.prototype.join.call(arguments, ' '));
    consoleError.apply(console, arguments);
  };

  // A cell's sort key: its data-sort number (null when it has no value), else its text.
  function sortKey(td) {
    var v = td.getAttribute('data-sort');
    if (v === null) return td.textContent.trim();
    return v === '' ? null : parseFloat(v);
  }

  // Sorts the table's rows by column `col`; rows without a value go last, ties keep the page's order.
  function sortTable(table, col, ascending) {
    var body = table.tBodies[0];
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = sortKey(a.cells[col]), y = sortKey(b.cells[col]);
      var order = a.getAttribute('data-order') - b.getAttribute('data-order');
      if (x === null || y === null) return (x === null) - (y === null) || order;
      if (x < y) return ascending ? -1 : 1;
      if (x > y) return ascending ? 1 : -1;
      return order;
    });
    rows.forEach(function (r) { body.appendChild(r); });
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th, i) {
      if (i === col) th.setAttribute('aria-sort', ascending ? 'ascending' : 'descending');
      else th.removeAttribute('aria-sort');
    });
  }

  // Back to the order the page was written in.
  function restoreOrder(table) {
    var body = table.tBodies[0];
    Array.prototype.slice.call(body.rows)
      .sort(function (a, b) { return a.getAttribute('data-order') - b.getAttribute('data-order'); })
      .forEach(function (r) { body.appendChild(r); });
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th) { th.removeAttribute('aria-sort'); });
  }

  document.querySelectorAll('table.sortable').forEach(function (table) {
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th, col) {
      th.addEventListener('click', function () {
        sortTable(table, col, th.getAttribute('aria-sort') !== 'ascending');
      });
    });
  });

  // A link to a drill-down opens it.
  function openTarget() {
    var id = decodeURIComponent(location.hash.slice(1));
    var target = id && document.getElementById(id);
    if (target && target.tagName === 'DETAILS') target.open = true;
  }
  window.addEventListener('hashchange', openTarget);
  openTarget();

  // Whether a column reads in order after a click: values ascending (or descending), empty ones last.
  function columnInOrder(table, col, ascending) {
    var seenEmpty = false, previous;
    return Array.prototype.every.call(table.tBodies[0].rows, function (row) {
      var key = sortKey(row.cells[col]);
      if (key === null) { seenEmpty = true; return true; }
      if (seenEmpty) return false;
      var ok = previous === undefined || (ascending ? !(key < previous) : !(key > previous));
      previous = key;
      return ok;
    });
  }

  function selfTest() {
    var result = { tables: [], figures: { count: 0, broken: [] }, curves: { count: 0, empty: [] },
                   drilldown: null, problems: problems };
    var pass = true;
    document.querySelectorAll('table.sortable').forEach(function (table) {
      var headers = table.tHead.rows[0].cells, failures = [];
      Array.prototype.forEach.call(headers, function (th, col) {
        th.dispatchEvent(new MouseEvent('click', { bubbles: true }));
        if (!columnInOrder(table, col, true)) failures.push(th.textContent + ' ascending');
        th.dispatchEvent(new MouseEvent('click', { bubbles: true }));
        if (!columnInOrder(table, col, false)) failures.push(th.textContent + ' descending');
      });
      restoreOrder(table);
      result.tables.push({ id: table.id, columns: headers.length, rows: table.tBodies[0].rows.length, failures: failures });
      if (failures.length) pass = false;
    });
    document.querySelectorAll('img.figure').forEach(function (img) {
      result.figures.count += 1;
      if (!img.complete || img.naturalWidth === 0) { result.figures.broken.push(img.alt); pass = false; }
    });
    document.querySelectorAll('svg.seed-curves').forEach(function (svg) {
      result.curves.count += 1;
      var lines = svg.querySelectorAll('polyline');
      var drawn = lines.length > 0 && Array.prototype.every.call(lines, function (l) { return l.getTotalLength() > 0 || l.points.length === 1; });
      if (!drawn) { result.curves.empty.push(svg.closest('details').id); pass = false; }
    });
    // rliable's figures: their points and profile lines are drawn (non-empty geometry).
    result.rliable = {
      poi: document.querySelectorAll('svg.poi-plot circle.point').length,
      iqm: document.querySelectorAll('svg.iqm-plot circle.point').length,
      profiles: document.querySelectorAll('svg.profile').length,
      seed_dots: document.querySelectorAll('svg.seed-dots circle.seed').length,
      empty: []
    };
    document.querySelectorAll('svg.profile polyline').forEach(function (l) {
      if (!(l.getTotalLength() > 0)) { result.rliable.empty.push(l.textContent); pass = false; }
    });
    function finish() {
      if (problems.length) pass = false;
      var out = document.getElementById('selftest');
      out.textContent = JSON.stringify(result);
      out.setAttribute('data-status', pass ? 'pass' : 'fail');
    }
    // Following a Table I cell's link must open its drill-down (after the hashchange it causes).
    var link = document.querySelector('#table-i-cells td.cell a');
    if (!link) { finish(); return; }
    var target = document.getElementById(link.getAttribute('href').slice(1));
    var fallback = setTimeout(function () {
      result.drilldown = { target: target ? target.id : null, opened: false };
      pass = false;
      finish();
    }, 2000);
    window.addEventListener('hashchange', function () {
      clearTimeout(fallback);
      result.drilldown = { target: target ? target.id : null, opened: !!(target && target.open) };
      if (!result.drilldown.opened) pass = false;
      finish();
    }, { once: true });
    link.click();
  }
  window.addEventListener('load', function () {
    if (location.hash === '#selftest') selfTest();
  });
})();
)js";
}

}  // namespace rapid
