/* trunk-workbench per-case table: one row per case x model from the JSON block #wb-cases
 * ({columns: [{key, label, num}], rows: [{cells: {...}, case: id, figures: [names], view: bool}]}).
 * Click a header to sort (again: reverse); the inputs under the headers filter: text matches
 * substrings, numbers take "> 1", "<= 0.5", "= 3" or a range "1..5".  Checked by tests/report/.
 */
(function () {
  "use strict";
  var el = document.getElementById("wb-cases");
  var table = document.getElementById("wb-case-table");
  if (!el || !table) { return; }
  var data = JSON.parse(el.textContent);
  var cols = data.columns, rows = data.rows;
  var sortKey = null, sortDir = 1, filters = {};
  var thead = table.querySelector("thead"), tbody = table.querySelector("tbody");
  var count = document.getElementById("wb-case-count");

  function fmt(v, num) {
    if (v === null || v === undefined || v === "") { return ""; }
    if (!num || typeof v !== "number") { return String(v); }
    if (v === 0) { return "0"; }
    var a = Math.abs(v);
    return (a >= 1e4 || a < 1e-3) ? v.toExponential(2) : String(Number(v.toPrecision(4)));
  }
  function test(f, v, num) {
    f = f.trim();
    if (!f) { return true; }
    if (num) {
      var m = f.match(/^(-?[\d.eE+-]+)\s*\.\.\s*(-?[\d.eE+-]+)$/);
      if (m) { return v !== null && v >= Number(m[1]) && v <= Number(m[2]); }
      m = f.match(/^(<=|>=|<|>|=)\s*(-?[\d.eE+-]+)$/);
      if (m) {
        if (v === null || v === undefined || v === "") { return false; }
        var x = Number(m[2]);
        return m[1] === "<" ? v < x : m[1] === ">" ? v > x : m[1] === "<=" ? v <= x : m[1] === ">=" ? v >= x : v === x;
      }
    }
    return fmt(v, num).toLowerCase().indexOf(f.toLowerCase()) >= 0;
  }
  function header() {
    var tr = document.createElement("tr"), tf = document.createElement("tr");
    cols.forEach(function (c) {
      var th = document.createElement("th");
      th.textContent = c.label + (sortKey === c.key ? (sortDir > 0 ? " \u25b2" : " \u25bc") : "");
      th.title = "sort by " + c.label;
      th.className = "sortable";
      th.addEventListener("click", function () { sortDir = sortKey === c.key ? -sortDir : 1; sortKey = c.key; header(); render(); });
      tr.appendChild(th);
      var tdf = document.createElement("th"), inp = document.createElement("input");
      inp.type = "search"; inp.placeholder = c.num ? "> 1, 0..5" : "filter"; inp.value = filters[c.key] || "";
      inp.setAttribute("aria-label", "filter " + c.label);
      inp.addEventListener("input", function () { filters[c.key] = inp.value; render(); });
      tdf.appendChild(inp); tf.appendChild(tdf);
    });
    var th = document.createElement("th"); th.textContent = "figures / 3-D"; tr.appendChild(th); tf.appendChild(document.createElement("th"));
    thead.innerHTML = ""; thead.appendChild(tr); thead.appendChild(tf);
  }
  function render() {
    var list = rows.filter(function (r) {
      return cols.every(function (c) { return test(filters[c.key] || "", r.cells[c.key], c.num); });
    });
    if (sortKey !== null) {
      var num = cols.filter(function (c) { return c.key === sortKey; })[0].num;
      list.sort(function (a, b) {
        var x = a.cells[sortKey], y = b.cells[sortKey];
        var ex = x === null || x === undefined || x === "", ey = y === null || y === undefined || y === "";
        if (ex || ey) { return ex === ey ? 0 : ex ? 1 : -1; }
        return sortDir * (num ? x - y : String(x).localeCompare(String(y)));
      });
    }
    var frag = document.createDocumentFragment();
    list.forEach(function (r) {
      var tr = document.createElement("tr");
      if (r.cells.status !== "ok") { tr.className = "failed"; }
      tr.id = "case-" + r.case + "-" + r.cells.model;
      cols.forEach(function (c) {
        var td = document.createElement("td"); td.textContent = fmt(r.cells[c.key], c.num);
        if (c.num) { td.className = "num"; }
        tr.appendChild(td);
      });
      var td = document.createElement("td");
      r.figures.forEach(function (f) {
        var a = document.createElement("a"); a.href = "#fig-" + f; a.textContent = f; td.appendChild(a); td.appendChild(document.createTextNode(" "));
      });
      if (r.view) {
        var b = document.createElement("button"); b.type = "button"; b.textContent = "3-D";
        b.addEventListener("click", function () { if (window.wbShowCase) { window.wbShowCase(r.case); } });
        td.appendChild(b);
      }
      tr.appendChild(td);
      frag.appendChild(tr);
    });
    tbody.innerHTML = ""; tbody.appendChild(frag);
    count.textContent = list.length + " of " + rows.length + " rows shown";
    table.setAttribute("data-rows", String(list.length));
  }
  header(); render();
})();
