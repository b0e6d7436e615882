/* wheelkin: keyboard access to wide equations, and animations under reduced motion.
   Added to every page by tools/accessibility.py (its docstring says why);
   tests/browser/test_accessibility.py checks both. */
(function () {
  "use strict";

  /* A displayed equation wider than its column scrolls sideways: it becomes a tab stop, so
     that a keyboard reader can reach it and scroll it with the arrow keys (the theme does
     the same for wide code blocks and tables). One that fits is no tab stop. */
  function equationTabStops() {
    var boxes = document.querySelectorAll('mjx-container[display="true"]');
    for (var i = 0; i < boxes.length; i++) {
      var box = boxes[i];
      if (box.scrollWidth > box.clientWidth + 1) {
        if (box.getAttribute("tabindex") !== "0") {
          box.setAttribute("tabindex", "0");
          box.setAttribute("data-wheelkin-scrolls", "");
        }
      } else if (box.hasAttribute("data-wheelkin-scrolls")) {
        box.removeAttribute("tabindex");
        box.removeAttribute("data-wheelkin-scrolls");
      }
    }
  }

  var pending = null;
  function later() {
    if (pending !== null) window.clearTimeout(pending);
    pending = window.setTimeout(function () { pending = null; equationTabStops(); }, 150);
  }

  /* Under prefers-reduced-motion an animation plays once and stops at its last frame
     instead of looping (it never starts by itself in any case: the reader presses Play). */
  var reduce = window.matchMedia ? window.matchMedia("(prefers-reduced-motion: reduce)") : null;
  function playOnce() {
    if (!reduce || !reduce.matches) return;
    var once = document.querySelectorAll('form.anim-state input[type="radio"][value="once"]');
    for (var i = 0; i < once.length; i++) once[i].checked = true;
  }

  /* A folded answer's show/hide button (sphinx-togglebutton) is called "Toggle hidden
     content" on every fold; it takes the fold's title instead ("Answer", "Solution"), and
     announces its state as it already does (aria-expanded). */
  function nameToggles() {
    var buttons = document.querySelectorAll(".admonition-title > button.toggle-button");
    for (var i = 0; i < buttons.length; i++) {
      var title = buttons[i].parentElement.textContent.replace(/\s+/g, " ").trim();
      if (title) buttons[i].setAttribute("aria-label", title);
    }
  }

  /* The module index's group togglers (Sphinx's doctools.js) are images that only a mouse
     can click: each becomes a button, named after its group, that Enter and Space press, and
     that says whether its group is shown. */
  function indexTogglers() {
    var imgs = document.querySelectorAll("img.toggler");
    for (var i = 0; i < imgs.length; i++) {
      var img = imgs[i];
      var row = img.closest("tr");
      var code = row ? row.querySelector("code") : null;
      var group = code ? code.textContent.trim() : "this group";
      img.setAttribute("role", "button");
      img.setAttribute("tabindex", "0");
      img.setAttribute("aria-label", "Submodules of " + group);
      var sync = (function (el) {
        return function () {
          el.setAttribute("aria-expanded", /minus\.png$/.test(el.src) ? "true" : "false");
        };
      })(img);
      sync();
      img.addEventListener("click", sync);
      img.addEventListener("keydown", function (event) {
        if (event.key === "Enter" || event.key === " ") {
          event.preventDefault();
          event.currentTarget.click();
        }
      });
    }
  }

  /* Once the page and the theme's scripts have run (the fold buttons are theirs). */
  function start() {
    nameToggles();
    indexTogglers();
    equationTabStops();
    var main = document.getElementById("main-content") || document.body;
    /* MathJax typesets after the page has loaded: its output is a change of the page. */
    new MutationObserver(later).observe(main, {childList: true, subtree: true});
    window.addEventListener("resize", later);
    if (window.MathJax && window.MathJax.startup && window.MathJax.startup.promise) {
      window.MathJax.startup.promise.then(equationTabStops);
    }
    if (reduce && reduce.addEventListener) reduce.addEventListener("change", playOnce);
  }

  playOnce();  /* before the reader can press Play */
  if (document.readyState === "complete") {
    start();
  } else {
    window.addEventListener("load", start);
  }
})();
