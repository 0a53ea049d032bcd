/* Self-test hook for the browser tests: with the page opened as report.html#selftest, log one
 * line "wb-selftest {json}" (table rows, drawn canvas pixels, viewer cases) and nothing else. */
(function () {
  "use strict";
  if (window.location.hash !== "#selftest") { return; }
  window.addEventListener("load", function () {
    var t = document.getElementById("wb-case-table"), c = document.querySelector("#wb-viewer canvas");
    var s = document.getElementById("wb-scenes");
    console.log("wb-selftest " + JSON.stringify({
      rows: t ? Number(t.getAttribute("data-rows")) : -1,
      pixels: c ? Number(c.getAttribute("data-drawn-pixels")) : -1,
      cases: s ? JSON.parse(s.textContent).cases.length : -1,
      figures: document.querySelectorAll("figure[data-figure]").length
    }));
  });
})();
