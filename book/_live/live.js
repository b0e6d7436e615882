/* Live pages (`make serve-live`, tools/serve_live.py): this page's code cells run against a
 * local Jupyter server, through Thebe.
 *
 * tools/serve_live.py injects this script, live.css and a JSON configuration
 * (#wk-live-config: the server's URL and token, the page's notebook, where Thebe is) into the
 * pages of notebooks; the static site never loads it. It adds one control, "Make this page
 * live". Its click loads Thebe (vendored), starts a kernel for the page's notebook in the
 * notebook's folder, turns every code cell into an editor with a run button (Shift-Enter runs
 * it too), runs the page's set-up cell (its first code cell) and every live panel's cell (a
 * panel that needs more gets the cells above it run first), and shows each panel where its
 * precomputed view was. A cell's new output replaces its stored
 * one. Nothing is loaded from outside the site and the local server: Thebe fetches require.js
 * from a CDN by a fixed URL, and that one request is answered with the site's own copy.
 */
(function () {
  "use strict";

  var configNode = document.getElementById("wk-live-config");
  if (!configNode) { return; }
  var config = JSON.parse(configNode.textContent);
  var THEBE_REQUIREJS = "https://cdnjs.cloudflare.com/ajax/libs/require.js/2.3.6/require.min.js";
  var state = window.wheelkinLive = {status: "idle", timings: {}};

  function mainColumn() {
    return document.querySelector("#main-content article") ||
      document.querySelector("main") || document.body;
  }

  function codeCells() {
    return Array.prototype.filter.call(mainColumn().querySelectorAll("div.cell"), function (cell) {
      return cell.querySelector(".cell_input div.highlight");
    });
  }

  function setStatus(bar, text, kind) {
    state.status = kind;
    bar.setAttribute("data-status", kind);
    bar.querySelector(".wk-live-status").textContent = text;
  }

  // Thebe asks a CDN for require.js (for third-party widgets; the book uses only the core
  // ones it bundles): serve the site's vendored copy instead.
  function keepRequireJsLocal() {
    var original = window.fetch.bind(window);
    window.fetch = function (resource, init) {
      var url = typeof resource === "string" ? resource : resource && resource.url;
      if (url === THEBE_REQUIREJS) { return original(config.requireJs, init); }
      return original(resource, init);
    };
  }

  function load(tag, attributes) {
    return new Promise(function (resolve, reject) {
      var node = document.createElement(tag);
      Object.keys(attributes).forEach(function (key) { node.setAttribute(key, attributes[key]); });
      node.onload = resolve;
      node.onerror = function () { reject(new Error("could not load " + (attributes.src || attributes.href))); };
      document.head.appendChild(node);
    });
  }

  // Math in a re-run cell's output: Thebe's typesetter is MathJax 2 from a CDN, so it is off;
  // the page's own MathJax 3 typesets LaTeX and Markdown outputs instead.
  function typeset(output) {
    if (!window.MathJax || !MathJax.typesetPromise) { return Promise.resolve(); }
    var nodes = [];
    output.querySelectorAll(".jp-RenderedLatex").forEach(function (node) {
      var tex = node.textContent.trim().replace(/^\$\$?|\$\$?$/g, "");
      node.textContent = "\\[" + tex + "\\]";
      nodes.push(node);
    });
    output.querySelectorAll(".jp-RenderedMarkdown, .jp-RenderedHTMLCommon").forEach(function (node) {
      var walker = document.createTreeWalker(node, NodeFilter.SHOW_TEXT);
      var texts = [];
      while (walker.nextNode()) {
        if (!walker.currentNode.parentElement.closest("code, pre")) { texts.push(walker.currentNode); }
      }
      texts.forEach(function (text) {
        text.nodeValue = text.nodeValue
          .replace(/\$\$([^$]+)\$\$/g, "\\[$1\\]").replace(/\$([^$\n]+)\$/g, "\\($1\\)");
      });
      nodes.push(node);
    });
    nodes.forEach(function (node) { node.classList.add("math"); });
    return nodes.length ? MathJax.typesetPromise(nodes) : Promise.resolve();
  }

  // Where a cell's new output goes: in place of its stored output (or of its precomputed view).
  function placeOutputs(cells) {
    var byId = {};
    cells.forEach(function (cell) {
      var box = cell.querySelector(".thebe-cell");
      if (!box) { return; }
      var output = box.querySelector(".thebe-output");
      var stored = cell.querySelector(":scope > .cell_output");
      var view = cell.querySelector(":scope > .wk-precomputed");
      var anchor = stored || view;
      if (output) {
        if (anchor) { cell.insertBefore(output, anchor); } else { cell.appendChild(output); }
      }
      byId[box.getAttribute("data-thebe-id")] = {cell: cell, output: output, stored: stored,
                                                  view: view};
    });
    return byId;
  }

  function wrapExecute(notebook, byId) {
    notebook.cells.forEach(function (thebeCell) {
      var where = byId[thebeCell.id];
      if (!where) { return; }
      var execute = thebeCell.execute.bind(thebeCell);
      thebeCell.execute = function (source) {
        if (where.stored) { where.stored.hidden = true; }
        where.cell.setAttribute("data-wk-run", "running");
        return Promise.resolve(execute(source)).then(function (result) {
          where.cell.setAttribute("data-wk-run", "done");
          if (where.view && where.output && where.output.querySelector(".jupyter-widgets, .widget-vbox")) {
            where.view.hidden = true;
          }
          return typeset(where.output).then(function () { return result; });
        });
      };
    });
  }

  function waitForWidgets(output, timeout) {
    return new Promise(function (resolve) {
      var start = performance.now();
      (function poll() {
        if (output.querySelector(".widget-vbox img, .jupyter-widgets img") ||
            performance.now() - start > timeout) { resolve(); return; }
        setTimeout(poll, 50);
      })();
    });
  }

  async function goLive(bar, button) {
    button.disabled = true;
    setStatus(bar, "Starting a kernel for this page…", "starting");
    var clicked = performance.now();
    try {
      keepRequireJsLocal();
      await load("link", {rel: "stylesheet", href: config.thebeCss});
      await load("script", {src: config.thebe});
      var cells = codeCells();
      cells.forEach(function (cell) {
        var source = cell.querySelector(".cell_input div.highlight");
        // The copy button's label is text inside the code block: not code.
        source.querySelectorAll("button.copybtn").forEach(function (b) { b.remove(); });
        source.setAttribute("data-wk-live-source", "");
      });
      var found = await window.thebe.bootstrap({
        useBinder: false, useJupyterLite: false, requestKernel: true,
        selector: "[data-wk-live-source]", outputSelector: "[data-wk-live-no-output]",
        mountStatusWidget: false, mountActivateWidget: false,
        mountRunButton: true, mountRunAllButton: false,
        mountRestartButton: true, mountRestartAllButton: false,
        serverSettings: {baseUrl: config.baseUrl, wsUrl: config.wsUrl, token: config.token,
                         appendToken: true},
        kernelOptions: {kernelName: config.kernelName, path: config.notebook},
        mathjaxUrl: "page", mathjaxConfig: "",
        codeMirrorConfig: {theme: "default", lineNumbers: false},
      });
      if (!found || !found.session) { throw new Error("the local server started no kernel"); }
      state.timings.kernelReadyMs = performance.now() - clicked;
      var byId = placeOutputs(cells);
      wrapExecute(found.notebook, byId);
      setStatus(bar, "Kernel ready: setting up the page and its live panels…", "setting-up");
      var all = found.notebook.cells;
      var panels = all.filter(function (c) { return byId[c.id] && byId[c.id].view; });
      var ran = {};
      async function run(cell) {
        ran[cell.id] = true;
        var result = await cell.execute(cell.source);
        return !(result && result.error && result.error.length);
      }
      // The set-up cell (imports and style), then each panel. A panel that needs a name from
      // a later cell than the set-up (a NameError) gets every cell above it run in order
      // first, as the notebook runs them, and runs again.
      if (all.length) { await run(all[0]); }
      for (var k = 0; k < panels.length; k++) {
        if (!(await run(panels[k]))) {
          for (var i = 0; i < all.indexOf(panels[k]); i++) {
            if (!ran[all[i].id]) { await run(all[i]); }
          }
          await run(panels[k]);
        }
      }
      for (var j = 0; j < panels.length; j++) {
        await waitForWidgets(byId[panels[j].id].output, 15000);
        byId[panels[j].id].view.hidden = true;
      }
      state.timings.pageReadyMs = performance.now() - clicked;
      state.notebook = found.notebook;
      setStatus(bar, "Live: every code cell is editable; Shift-Enter or its run button runs " +
        "it" + (panels.length ? ", and the panels' sliders take any value." : "."), "live");
      document.body.setAttribute("data-wk-live", "ready");
    } catch (error) {
      setStatus(bar, "Could not make the page live (" + error.message + "). Is `make " +
        "serve-live` still running?", "error");
      button.disabled = false;
    }
  }

  function stopKernel() {
    var session = window.thebe && window.thebe.session;
    var id = session && session.connection && session.connection.id;
    if (!id) { return; }
    fetch(config.baseUrl + "/api/sessions/" + id + "?token=" + encodeURIComponent(config.token),
          {method: "DELETE", keepalive: true, mode: "cors"}).catch(function () {});
  }

  function setUp() {
    if (!codeCells().length) { return; }
    var bar = document.createElement("div");
    bar.className = "wk-live-bar";
    bar.setAttribute("data-status", "idle");
    var button = document.createElement("button");
    button.type = "button";
    button.className = "wk-live-start";
    button.textContent = "Make this page live";
    var status = document.createElement("span");
    status.className = "wk-live-status";
    status.setAttribute("role", "status");
    status.setAttribute("aria-live", "polite");
    status.textContent = "Runs this page's code and panels in a kernel on this computer.";
    bar.appendChild(button);
    bar.appendChild(status);
    var column = mainColumn();
    column.insertBefore(bar, column.firstChild);
    button.addEventListener("click", function () { goLive(bar, button); });
    window.addEventListener("pagehide", stopKernel);
  }

  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", setUp);
  } else {
    setUp();
  }
})();
