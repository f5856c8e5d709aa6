// gclint's HTML page: its one script, run under the page's nonce (html.py: page_script).  Plain JavaScript, no
// library, nothing fetched: the findings' severity filters, and the toolpath viewer of each job.
//
// A figure.toolpath holds its data as JSON (html.py: build_plot): "unit" mm per step and "origin"; "heads"
// (name, colour); "layers", each {"z": [low, high] or null, "p": [[head, steps, runs], ...]}, where steps are
// x, y of the first point then the step to each next one, and runs alternate counts of travel and working
// strokes (travel first); "fit" (the part) and "all" (every move) as boxes in steps; "markers":
// [x, y, layer, line, severity] for the flagged lines, with "severities" and their "colors".
(function () {
  "use strict";
  var body = document.body;
  var viewers = [];

  document.querySelectorAll("input[data-severity]").forEach(function (box) {
    box.addEventListener("change", function () {
      body.classList.toggle("hidden-" + box.dataset.severity, !box.checked);
      viewers.forEach(function (v) { v.draw(); });
    });
  });

  function select(section, line) {
    section.querySelectorAll(".sel").forEach(function (el) { el.classList.remove("sel"); });
    section.querySelectorAll('tr[data-line="' + line + '"]').forEach(function (el) { el.classList.add("sel"); });
  }

  function zText(z) {
    return z.toFixed(2).replace(/\.?0+$/, "");
  }

  function Viewer(fig) {
    var data = JSON.parse(fig.dataset.toolpath);
    var section = fig.closest("section") || document.body;
    var canvas = fig.querySelector("canvas.tp-canvas");
    var ctx = canvas.getContext("2d");
    var slider = fig.querySelector("input.tp-layer");
    var label = fig.querySelector(".tp-label");
    var layers = data.layers;
    var n = layers.length;
    var shown = {travel: false, below: true};
    var hidden = {};  // head index -> true when switched off in the legend
    var view = {s: 1, tx: 0, ty: 0};  // screen = (x * s + tx, -y * s + ty), in CSS pixels
    var fitScale = 1;
    var current = n - 1;
    var selected = null;  // the line of the selected marker
    var paths = [];  // per layer, built when first drawn: [{head, work: Path2D, travel: Path2D}]
    var width = 0, height = 0, ratio = 1;
    var under = null;  // the layers below the shown one, before they are faded
    var pending = false;
    var self = this;

    function build(i) {
      if (paths[i]) return paths[i];
      var out = [];
      layers[i].p.forEach(function (rec) {
        var steps = rec[1], runs = rec[2];
        var work = new Path2D(), travel = new Path2D();
        var x = steps[0], y = steps[1], k = 2;
        for (var r = 0; r < runs.length; r++) {
          var count = runs[r];
          if (!count) continue;
          var path = r % 2 ? work : travel;
          path.moveTo(x, -y);
          for (var j = 0; j < count; j++) {
            x += steps[k++];
            y += steps[k++];
            path.lineTo(x, -y);
          }
        }
        out.push({head: rec[0], work: work, travel: travel});
      });
      paths[i] = out;
      return out;
    }

    function layerText(i) {
      if (!n) return "no layers";
      var text = "layer " + (i + 1) + " of " + n;
      var z = layers[i].z;
      if (z) {
        var low = zText(z[0]), high = zText(z[1]);
        text += low === high ? ", Z " + low + " mm" : ", Z " + low + " to " + high + " mm";
      }
      return text;
    }

    function severityShown(index) {
      return !body.classList.contains("hidden-" + data.severities[index]);
    }

    function markerShown(m) {
      return severityShown(m[4]) && (m[2] === current || (shown.below && m[2] < current));
    }

    this.draw = function () {
      if (pending) return;
      pending = true;
      requestAnimationFrame(paint);
    };

    function paint() {
      pending = false;
      if (!width) return;
      var s = view.s;
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      ctx.fillStyle = "#fff";
      ctx.fillRect(0, 0, canvas.width, canvas.height);
      ctx.setTransform(s * ratio, 0, 0, s * ratio, view.tx * ratio, view.ty * ratio);
      ctx.lineJoin = "round";
      ctx.lineCap = "round";
      if (shown.below && current > 0) {
        // the layers below, drawn whole on their own canvas, then laid on faded: one even tint, however
        // many layers there are.  While a drag pans the view they are moved as they are (drawn again at
        // its end), so a big job pans smoothly.
        var key = [s, current, canvas.width, canvas.height, Object.keys(hidden).filter(function (h) {
          return hidden[h];
        }).join()].join(" ");
        var dx = 0, dy = 0;
        if (!under || key !== under.key || (!drag && (view.tx !== under.tx || view.ty !== under.ty))) {
          if (!under) under = document.createElement("canvas");
          if (under.width !== canvas.width || under.height !== canvas.height) {
            under.width = canvas.width;
            under.height = canvas.height;
          }
          var low = under.getContext("2d");
          low.setTransform(1, 0, 0, 1, 0, 0);
          low.clearRect(0, 0, under.width, under.height);
          low.setTransform(s * ratio, 0, 0, s * ratio, view.tx * ratio, view.ty * ratio);
          low.lineJoin = "round";
          low.lineCap = "round";
          low.lineWidth = 1 / s;
          for (var i = 0; i < current; i++) {
            build(i).forEach(function (p) {
              if (hidden[p.head]) return;
              low.strokeStyle = data.heads[p.head].color;
              low.stroke(p.work);
            });
          }
          under.key = key;
          under.tx = view.tx;
          under.ty = view.ty;
        } else {
          dx = (view.tx - under.tx) * ratio;
          dy = (view.ty - under.ty) * ratio;
        }
        ctx.setTransform(1, 0, 0, 1, 0, 0);
        ctx.globalAlpha = 0.22;
        ctx.drawImage(under, dx, dy);
        ctx.setTransform(s * ratio, 0, 0, s * ratio, view.tx * ratio, view.ty * ratio);
      }
      var top = n ? build(current) : [];
      if (shown.travel) {
        ctx.globalAlpha = 0.7;
        ctx.lineWidth = 0.8 / s;
        ctx.setLineDash([4 / s, 3 / s]);
        top.forEach(function (p) {
          if (hidden[p.head]) return;
          ctx.strokeStyle = data.heads[p.head].color;
          ctx.stroke(p.travel);
        });
        ctx.setLineDash([]);
      }
      ctx.globalAlpha = 1;
      ctx.lineWidth = 1.6 / s;
      top.forEach(function (p) {
        if (hidden[p.head]) return;
        ctx.strokeStyle = data.heads[p.head].color;
        ctx.stroke(p.work);
      });
      ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
      data.markers.forEach(function (m) {
        if (!markerShown(m)) return;
        var here = m[2] === current;
        var at = screen(m);
        ctx.globalAlpha = here ? 0.95 : 0.45;
        ctx.beginPath();
        ctx.arc(at[0], at[1], here ? 5 : 3, 0, 2 * Math.PI);
        ctx.fillStyle = data.colors[m[4]];
        ctx.fill();
        ctx.lineWidth = 1;
        ctx.strokeStyle = "#fff";
        ctx.stroke();
        if (m[3] === selected) {
          ctx.globalAlpha = 1;
          ctx.beginPath();
          ctx.arc(at[0], at[1], 9, 0, 2 * Math.PI);
          ctx.lineWidth = 2;
          ctx.strokeStyle = "#000";
          ctx.stroke();
        }
      });
      ctx.globalAlpha = 1;
      fig.dataset.drawn = String(current + 1);
    }

    function screen(m) {
      return [m[0] * view.s + view.tx, -m[1] * view.s + view.ty];
    }

    function fit(box) {
      var w = Math.max(box[2] - box[0], 0), h = Math.max(box[3] - box[1], 0);
      var s = Math.min(width / (w || 1), height / (h || 1)) * 0.92;
      if (!w && !h) s = Math.min(width, height) / (10 / data.unit);  // one point: a 10 mm field
      if (!isFinite(s) || s <= 0) s = 1;
      view.s = s;
      view.tx = width / 2 - (box[0] + box[2]) / 2 * s;
      view.ty = height / 2 + (box[1] + box[3]) / 2 * s;
      self.draw();
    }

    function zoom(factor, px, py) {
      if (px === undefined) { px = width / 2; py = height / 2; }
      var s = Math.min(Math.max(view.s * factor, fitScale / 100), fitScale * 5000);
      var wx = (px - view.tx) / view.s, wy = (py - view.ty) / view.s;
      view.s = s;
      view.tx = px - wx * s;
      view.ty = py - wy * s;
      self.draw();
    }

    function pan(dx, dy) {
      view.tx += dx;
      view.ty += dy;
      self.draw();
    }

    function setLayer(i) {
      if (!n) return;
      current = Math.min(Math.max(i, 0), n - 1);
      if (slider) slider.value = String(current + 1);
      if (label) label.textContent = layerText(current);
      self.draw();
    }

    function resize() {
      var rect = canvas.getBoundingClientRect();
      var dpr = window.devicePixelRatio || 1;
      if (!rect.width || !rect.height) return;
      if (rect.width === width && rect.height === height && dpr === ratio) return;
      var first = !width;
      var cx = (width / 2 - view.tx) / view.s, cy = (height / 2 - view.ty) / view.s;
      width = rect.width;
      height = rect.height;
      ratio = dpr;
      canvas.width = Math.round(width * ratio);
      canvas.height = Math.round(height * ratio);
      if (first) {
        fit(data.fit);
        fitScale = view.s;
      } else {
        view.tx = width / 2 - cx * view.s;
        view.ty = height / 2 - cy * view.s;
      }
      paint();  // (now: a canvas given a new size is blank until it is drawn again)
    }

    function markerAt(px, py) {
      var best = null, bestDist = 64;  // within 8 px
      data.markers.forEach(function (m) {
        if (!markerShown(m)) return;
        var at = screen(m), dx = at[0] - px, dy = at[1] - py, d = dx * dx + dy * dy;
        if (d < bestDist || (d === bestDist && (!best || m[2] === current))) { best = m; bestDist = d; }
      });
      return best;
    }

    function offset(e) {
      var rect = canvas.getBoundingClientRect();
      return [e.clientX - rect.left, e.clientY - rect.top];
    }

    // -- from a finding to its marker, and back -------------------------------------------------------------

    this.show = function (line) {
      var m = null;
      data.markers.forEach(function (k) { if (k[3] === line && !m) m = k; });
      if (!m) return false;
      selected = line;
      setLayer(m[2]);
      var at = screen(m);
      if (at[0] < 0 || at[0] > width || at[1] < 0 || at[1] > height) pan(width / 2 - at[0], height / 2 - at[1]);
      fig.scrollIntoView({block: "nearest"});
      self.draw();
      return true;
    };

    function toFinding(m) {
      selected = m[3];
      select(section, m[3]);
      var row = section.querySelector('tr[data-line="' + m[3] + '"]');
      if (row) row.scrollIntoView({block: "center"});
      self.draw();
    }

    function findingText(m) {
      var texts = [];
      section.querySelectorAll('tr[data-line="' + m[3] + '"]').forEach(function (row) {
        var code = row.querySelector(".badge"), cells = row.querySelectorAll("td");
        var message = cells.length > 2 ? cells[2].firstChild.textContent.trim() : "";
        texts.push((code ? code.textContent + " " : "") + message);
      });
      return "line " + m[3] + ": " + (texts.join("; ") || data.severities[m[4]]) + " (click: the finding)";
    }

    // -- input ------------------------------------------------------------------------------------------------

    var drag = null;
    canvas.addEventListener("pointerdown", function (e) {
      if (e.button !== 0) return;
      drag = {x: e.clientX, y: e.clientY, moved: 0};
      canvas.setPointerCapture(e.pointerId);
      canvas.classList.add("dragging");
    });
    canvas.addEventListener("pointermove", function (e) {
      if (drag) {
        var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
        drag.moved += Math.abs(dx) + Math.abs(dy);
        drag.x = e.clientX;
        drag.y = e.clientY;
        pan(dx, dy);
        return;
      }
      var at = offset(e), m = markerAt(at[0], at[1]);
      canvas.classList.toggle("over-marker", !!m);
      canvas.title = m ? findingText(m) : "";
    });
    function release(e) {
      if (!drag) return;
      var click = drag.moved < 4;
      drag = null;
      canvas.classList.remove("dragging");
      self.draw();  // (the layers below, moved as they were during the drag, drawn again)
      if (click && e.type === "pointerup") {
        var at = offset(e), m = markerAt(at[0], at[1]);
        if (m) toFinding(m);
      }
    }
    canvas.addEventListener("pointerup", release);
    canvas.addEventListener("pointercancel", release);
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault();
      var dy = e.deltaY * (e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1);
      var at = offset(e);
      zoom(Math.exp(-dy * 0.0015), at[0], at[1]);
    }, {passive: false});
    canvas.addEventListener("dblclick", function (e) {
      var at = offset(e);
      zoom(2, at[0], at[1]);
    });
    canvas.addEventListener("keydown", function (e) {
      var step = e.shiftKey ? 160 : 40;
      var keys = {
        "+": function () { zoom(1.25); }, "=": function () { zoom(1.25); },
        "-": function () { zoom(0.8); }, "_": function () { zoom(0.8); },
        "0": function () { fit(data.fit); }, "f": function () { fit(data.fit); },
        "a": function () { fit(data.all); },
        "ArrowLeft": function () { pan(step, 0); }, "ArrowRight": function () { pan(-step, 0); },
        "ArrowUp": function () { pan(0, step); }, "ArrowDown": function () { pan(0, -step); },
        "PageUp": function () { setLayer(current + 1); }, "]": function () { setLayer(current + 1); },
        "PageDown": function () { setLayer(current - 1); }, "[": function () { setLayer(current - 1); },
        "Home": function () { setLayer(0); }, "End": function () { setLayer(n - 1); },
        "t": function () { toggle("travel"); }, "e": function () { toggle("below"); }
      };
      var act = keys[e.key] || keys[e.key.toLowerCase()];
      if (!act || e.ctrlKey || e.metaKey || e.altKey) return;
      e.preventDefault();
      act();
    });

    function toggle(name) {
      shown[name] = !shown[name];
      var box = fig.querySelector('input[data-opt="' + name + '"]');
      if (box) box.checked = shown[name];
      self.draw();
    }

    fig.querySelectorAll("button[data-act]").forEach(function (button) {
      button.addEventListener("click", function () {
        var act = button.dataset.act;
        if (act === "in") zoom(1.5);
        else if (act === "out") zoom(1 / 1.5);
        else if (act === "fit") fit(data.fit);
        else if (act === "all") fit(data.all);
        else if (act === "up") setLayer(current + 1);
        else if (act === "down") setLayer(current - 1);
      });
    });
    fig.querySelectorAll("input[data-opt]").forEach(function (box) {
      shown[box.dataset.opt] = box.checked;
      box.addEventListener("change", function () {
        shown[box.dataset.opt] = box.checked;
        self.draw();
      });
    });
    fig.querySelectorAll("button.tp-head").forEach(function (button) {
      button.addEventListener("click", function () {
        var head = Number(button.dataset.head);
        hidden[head] = !hidden[head];
        button.setAttribute("aria-pressed", String(!hidden[head]));
        self.draw();
      });
    });
    if (slider) {
      slider.addEventListener("input", function () { setLayer(Number(slider.value) - 1); });
    }

    if (typeof ResizeObserver === "function") new ResizeObserver(resize).observe(canvas);
    window.addEventListener("resize", resize);
    setLayer(current);
    resize();
  }

  // Each viewer starts when its figure first comes into sight (a page may hold many jobs), or when a
  // finding asks for its marker.
  var figures = Array.prototype.slice.call(document.querySelectorAll("figure.toolpath[data-toolpath]"));
  function viewerOf(fig) {
    if (!fig.viewer) {
      try {
        fig.viewer = new Viewer(fig);
        viewers.push(fig.viewer);
      } catch (err) {
        fig.dataset.failed = "1";
        console.error("gclint: the toolpath could not be drawn: " + err);
        return null;
      }
    }
    return fig.viewer;
  }
  if (typeof IntersectionObserver === "function") {
    var seen = new IntersectionObserver(function (entries) {
      entries.forEach(function (entry) {
        if (entry.isIntersecting) {
          seen.unobserve(entry.target);
          viewerOf(entry.target);
        }
      });
    }, {rootMargin: "200px"});
    figures.forEach(function (fig) { seen.observe(fig); });
  } else {
    figures.forEach(viewerOf);
  }

  document.querySelectorAll("section.file").forEach(function (section) {
    var fig = section.querySelector("figure.toolpath[data-toolpath]");
    section.querySelectorAll("tr[data-line]").forEach(function (row) {
      row.addEventListener("click", function () {
        select(section, row.dataset.line);
        if (fig && row.querySelector("button.goto")) {
          var viewer = viewerOf(fig);
          if (viewer) viewer.show(Number(row.dataset.line));
        }
      });
    });
  });

  body.dataset.ready = "1";
  console.log("gclint report ready: " + figures.length + " toolpath(s)");
})();
