/* Precomputed views of the live panels (tools/live_pages.py writes their HTML and images).
 *
 * Each view holds one image per grid position, named "<i>-<j>.png" after the index of each
 * control. This script shows the controls (hidden without JavaScript, so that nothing in a
 * page without it looks live and does nothing), and swaps the image as a control moves. Only
 * the image at the defaults is in the page; the others are fetched on first use, and the
 * images along a control's row are fetched ahead when the reader first touches it.
 */
(function () {
  "use strict";

  function setUp(view) {
    var base = view.getAttribute("data-base");
    var image = view.querySelector("img.wk-pc-image");
    var controls = Array.prototype.slice.call(view.querySelectorAll("[data-axis]"));
    var title = view.getAttribute("data-title") || "";
    var fixed = view.getAttribute("data-fixed") || "";
    var fetched = {};

    function index(control) { return parseInt(control.value, 10); }

    function fileAt(indices) { return base + indices.join("-") + ".png"; }

    function label(control) {
      var box = control.closest(".wk-pc-control");
      var text = box && box.querySelector("label");
      return text ? text.textContent : "";
    }

    function shown(control) {
      if (control.tagName === "SELECT") {
        return control.options[control.selectedIndex].textContent;
      }
      return JSON.parse(control.getAttribute("data-values"))[index(control)];
    }

    function prefetch(control) {
      // The whole row along this control, the others held where they are.
      var indices = controls.map(index);
      var count = control.tagName === "SELECT" ? control.options.length
                                                : parseInt(control.max, 10) + 1;
      for (var k = 0; k < count; k++) {
        indices[controls.indexOf(control)] = k;
        var url = fileAt(indices);
        if (!fetched[url]) {
          fetched[url] = true;
          var ahead = new Image();
          ahead.src = url;
        }
      }
    }

    function update() {
      var parts = controls.map(function (control) {
        var value = shown(control);
        if (control.tagName !== "SELECT") {
          control.setAttribute("aria-valuetext", value);
          var out = view.querySelector("output[for='" + control.id + "']");
          if (out) { out.textContent = value; }
        }
        return label(control) + " " + value;
      });
      var url = fileAt(controls.map(index));
      fetched[url] = true;
      image.src = url;
      image.alt = title + ": the panel's figure at " + parts.join("; ") +
        (fixed ? "; " + fixed : "");
      view.setAttribute("data-shown", controls.map(index).join("-"));
    }

    controls.forEach(function (control) {
      control.addEventListener("input", update);
      control.addEventListener("change", update);
      ["focus", "pointerdown"].forEach(function (kind) {
        control.addEventListener(kind, function () { prefetch(control); }, {once: true});
      });
    });
    var box = view.querySelector(".wk-pc-controls");
    if (box) { box.hidden = false; }
    view.classList.add("wk-pc-ready");
  }

  function start() {
    Array.prototype.forEach.call(document.querySelectorAll(".wk-precomputed"), setUp);
  }

  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", start);
  } else {
    start();
  }
})();
