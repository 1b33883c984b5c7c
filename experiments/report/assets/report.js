(function () {
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
