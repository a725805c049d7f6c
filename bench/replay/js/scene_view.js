// SPDX-License-Identifier: MIT
// Draws the scene at a step on the main canvas: static and kinematic bodies once in grey, every
// dynamic body once per engine in that engine's colour (lower engines with wider outlines, so
// boxes in the same place still show every engine), the scene's expectations, the failed checks
// and events of the moment, and the body under the pointer. Finds the body at a point.

// Engine colours; red is kept for failed checks.
const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf",
                 "#bcbd22"];
const FAIL_COLOUR = "#c62828";
const EXPECT_COLOUR = "#37474f";

function engineColour(k) {
  return PALETTE[k % PALETTE.length];
}

// "a,b,c" of a colour "#rrggbb", for translucent fills.
function rgbOf(hex) {
  const v = parseInt(hex.slice(1), 16);
  return ((v >> 16) & 255) + "," + ((v >> 8) & 255) + "," + (v & 255);
}

// A round number of metres near `target`: 1, 2 or 5 times a power of ten.
function niceLength(target) {
  const p = Math.pow(10, Math.floor(Math.log10(target)));
  const m = target / p;
  return (m < 2 ? 1 : m < 5 ? 2 : 5) * p;
}

class SceneView {
  constructor(canvas, model, camera, marks) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.model = model;
    this.camera = camera;
    this.marks = marks;
    this.shown = model.engines.map(() => true);
    // The smallest dynamic half extent: below a few pixels, per-body targets are clutter.
    this.minHalf = Infinity;
    for (let i = 0; i < model.count; i++) {
      if (model.kinds[i] === KIND_DYNAMIC)
        this.minHalf = Math.min(this.minHalf, model.half[2 * i], model.half[2 * i + 1]);
    }
  }

  resize() {
    const ratio = window.devicePixelRatio || 1;
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    this.canvas.width = Math.max(1, Math.round(w * ratio));
    this.canvas.height = Math.max(1, Math.round(h * ratio));
    this.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    this.camera.resize(w, h);
  }

  draw(step, hover) {
    const ctx = this.ctx, cam = this.camera;
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, cam.width, cam.height);
    this.drawGrid();
    this.drawFixed(step);
    const order = this.model.engines.map((e, k) => k).filter((k) => this.shown[k]);
    // Lower engines get wider outlines, so that boxes in one place still show every engine;
    // with thousands of boxes in view, thin outlines and no fill keep a frame cheap to raster.
    const crowded = this.visibleDynamic() * order.length > 4000;
    order.forEach((k, z) => this.drawEngine(k, step, crowded ? 1 : 1 + 2 * (order.length - 1 - z),
                                            !crowded));
    if (crowded) {
      ctx.fillStyle = "#5b6470";
      ctx.font = "11px system-ui, sans-serif";
      ctx.fillText("crowded view: 1-pixel outlines, the last engine on top; zoom in or untick " +
                   "engines to compare them", 8, 14);
    }
    this.drawExpectations(step);
    this.drawMarks(step);
    if (hover !== null && hover !== undefined) this.drawHover(hover, step);
    this.drawScaleBar();
  }

  drawGrid() {
    const ctx = this.ctx, cam = this.camera, v = cam.visible();
    const spacing = niceLength(80 / cam.scale);
    ctx.strokeStyle = "#eef0f3";
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (let x = Math.ceil(v.x0 / spacing) * spacing; x <= v.x1; x += spacing) {
      const px = Math.round(cam.toScreenX(x)) + 0.5;
      ctx.moveTo(px, 0);
      ctx.lineTo(px, cam.height);
    }
    for (let y = Math.ceil(v.y0 / spacing) * spacing; y <= v.y1; y += spacing) {
      const py = Math.round(cam.toScreenY(y)) + 0.5;
      ctx.moveTo(0, py);
      ctx.lineTo(cam.width, py);
    }
    ctx.stroke();
  }

  // Adds body i's box at centre p to the current path; false when it is off screen.
  addBox(i, p) {
    const cam = this.camera, m = this.model;
    const hx = m.half[2 * i] * cam.scale, hy = m.half[2 * i + 1] * cam.scale;
    const x = cam.toScreenX(p[0]), y = cam.toScreenY(p[1]);
    if (x + hx < 0 || x - hx > cam.width || y + hy < 0 || y - hy > cam.height) return false;
    this.ctx.rect(x - hx, y - hy, Math.max(2 * hx, 0.5), Math.max(2 * hy, 0.5));
    return true;
  }

  // Static bodies, and kinematic ones where the first engine has them: the scene moves them,
  // not the engines.
  drawFixed(step) {
    const ctx = this.ctx, m = this.model;
    for (const kind of [KIND_STATIC, KIND_KINEMATIC]) {
      ctx.beginPath();
      for (let i = 0; i < m.count; i++) {
        if (m.kinds[i] !== kind) continue;
        const p = kind === KIND_STATIC ? [m.centers[2 * i], m.centers[2 * i + 1]]
                                       : m.position(0, i, step);
        if (p) this.addBox(i, p);
      }
      ctx.fillStyle = kind === KIND_STATIC ? "#e4e6ea" : "#cfd3d9";
      ctx.fill();
      ctx.strokeStyle = kind === KIND_STATIC ? "#9aa1ab" : "#6f7782";
      ctx.lineWidth = 1;
      ctx.stroke();
    }
  }

  // The dynamic bodies in view as built: how crowded the view is.
  visibleDynamic() {
    const m = this.model, v = this.camera.visible();
    let n = 0;
    for (let i = 0; i < m.count; i++) {
      if (m.kinds[i] !== KIND_DYNAMIC) continue;
      const x = m.centers[2 * i], y = m.centers[2 * i + 1];
      n += x >= v.x0 && x <= v.x1 && y >= v.y0 && y <= v.y1;
    }
    return n;
  }

  drawEngine(k, step, width, fill) {
    const ctx = this.ctx, m = this.model;
    ctx.beginPath();
    for (let i = 0; i < m.count; i++) {
      if (m.kinds[i] !== KIND_DYNAMIC) continue;
      const p = m.position(k, i, step);
      if (p) this.addBox(i, p);
    }
    const colour = engineColour(k);
    if (fill) {
      ctx.fillStyle = "rgba(" + rgbOf(colour) + ",0.07)";
      ctx.fill();
    }
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.stroke();
  }

  // A cross with a circle of radius `r` metres around world point p.
  drawTarget(p, r, emphasis) {
    const ctx = this.ctx, cam = this.camera;
    const x = cam.toScreenX(p[0]), y = cam.toScreenY(p[1]);
    ctx.beginPath();
    ctx.moveTo(x - 6, y); ctx.lineTo(x + 6, y);
    ctx.moveTo(x, y - 6); ctx.lineTo(x, y + 6);
    ctx.lineWidth = emphasis ? 2 : 1;
    ctx.stroke();
    const radius = r * cam.scale;
    if (radius > 3) {
      ctx.beginPath();
      ctx.arc(x, y, radius, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }

  drawExpectations(step) {
    const ctx = this.ctx, cam = this.camera;
    ctx.save();
    ctx.strokeStyle = EXPECT_COLOUR;
    ctx.fillStyle = EXPECT_COLOUR;
    ctx.setLineDash([4, 3]);
    ctx.font = "11px system-ui, sans-serif";
    for (const e of this.marks.expectations) {
      if (!e.shownAt(step)) continue;
      const emphasis = e.checkedAt(step);
      if (e.targets) {
        const small = e.every && this.minHalf * cam.scale < 3;
        if (!small) e.targets.forEach((t) => this.drawTarget(t.at, e.tolerance, emphasis));
      }
      if (e.bounds) {
        ctx.lineWidth = emphasis ? 2 : 1;
        ctx.beginPath();
        for (const b of e.bounds) {
          if (b.axis === 0) {
            const x = cam.toScreenX(b.value);
            ctx.moveTo(x, 0); ctx.lineTo(x, cam.height);
            ctx.fillText(b.text, x + 3, 14);
          } else {
            const y = cam.toScreenY(b.value);
            ctx.moveTo(0, y); ctx.lineTo(cam.width, y);
            ctx.fillText(b.text, 4, y - 3);
          }
        }
        ctx.stroke();
      }
    }
    ctx.restore();
  }

  // The bodies of the failed checks (red) and events (the engine's colour, dashed) of this
  // moment, outlined a few pixels outside their box; one label per body names them all.
  drawMarks(step) {
    const ctx = this.ctx, cam = this.camera, m = this.model;
    const labels = new Map();  // body -> {x, y, texts, failed}
    ctx.save();
    for (const mark of this.marks.at(step)) {
      if (!this.shown[mark.engine]) continue;
      for (const body of mark.bodies) {
        const p = m.kinds[body] === KIND_STATIC ? [m.centers[2 * body], m.centers[2 * body + 1]]
                                                 : m.position(mark.engine, body, step);
        if (!p) continue;
        const hx = m.half[2 * body] * cam.scale + 4, hy = m.half[2 * body + 1] * cam.scale + 4;
        const x = cam.toScreenX(p[0]), y = cam.toScreenY(p[1]);
        ctx.strokeStyle = mark.failed ? FAIL_COLOUR : engineColour(mark.engine);
        ctx.lineWidth = mark.failed ? 2.5 : 1.5;
        ctx.setLineDash(mark.failed ? [] : [4, 3]);
        ctx.strokeRect(x - hx, y - hy, 2 * hx, 2 * hy);
        if (!labels.has(body)) labels.set(body, { x: x + hx + 3, y: y - hy + 10, texts: [], failed: false });
        const label = labels.get(body);
        if (!label.texts.includes(mark.short)) label.texts.push(mark.short);
        label.failed = label.failed || mark.failed;
      }
    }
    ctx.font = "bold 11px system-ui, sans-serif";
    const placed = [];  // label boxes drawn so far: a label moves down past them
    let shown = 0;
    for (const label of labels.values()) {
      if (shown++ >= 24) break;  // beyond that, the side panel lists them
      const lines = label.texts.slice(0, 4);
      const w = Math.max(...lines.map((t) => ctx.measureText(t).width));
      const h = 13 * lines.length;
      let y = label.y - 10;
      for (let tries = 0; tries < 20; tries++) {
        const clash = placed.find((r) => label.x < r.x + r.w && r.x < label.x + w &&
                                         y < r.y + r.h && r.y < y + h);
        if (!clash) break;
        y = clash.y + clash.h + 2;
      }
      placed.push({ x: label.x, y: y, w: w, h: h });
      ctx.fillStyle = label.failed ? FAIL_COLOUR : "#333333";
      lines.forEach((text, k) => ctx.fillText(text, label.x, y + 10 + 13 * k));
    }
    ctx.restore();
  }

  drawHover(body, step) {
    const ctx = this.ctx, m = this.model;
    ctx.save();
    ctx.setLineDash([]);
    ctx.lineWidth = 2;
    ctx.strokeStyle = "#000000";
    ctx.beginPath();
    this.model.engines.forEach((e, k) => {
      if (!this.shown[k] && m.kinds[body] === KIND_DYNAMIC) return;
      const p = m.kinds[body] === KIND_STATIC ? [m.centers[2 * body], m.centers[2 * body + 1]]
                                               : m.position(k, body, step);
      if (p) this.addBox(body, p);
    });
    ctx.stroke();
    ctx.restore();
  }

  drawScaleBar() {
    const ctx = this.ctx, cam = this.camera;
    const metres = niceLength(120 / cam.scale);
    const px = metres * cam.scale;
    const x1 = cam.width - 14, y = cam.height - 14;
    ctx.save();
    ctx.strokeStyle = "#333333";
    ctx.fillStyle = "#333333";
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(x1 - px, y - 4); ctx.lineTo(x1 - px, y); ctx.lineTo(x1, y); ctx.lineTo(x1, y - 4);
    ctx.stroke();
    ctx.font = "11px system-ui, sans-serif";
    ctx.textAlign = "center";
    ctx.fillText(formatNumber(metres, 3) + " m", x1 - px / 2, y - 6);
    ctx.restore();
  }

  // The body under canvas point (px, py) at a step (the smallest box there), or null.
  bodyAt(px, py, step) {
    const m = this.model;
    const w = this.camera.toWorld(px, py);
    let best = null, bestArea = Infinity;
    const consider = (i, p) => {
      if (!p) return;
      const hx = m.half[2 * i], hy = m.half[2 * i + 1];
      if (Math.abs(w[0] - p[0]) <= hx && Math.abs(w[1] - p[1]) <= hy && hx * hy < bestArea) {
        best = i;
        bestArea = hx * hy;
      }
    };
    for (let i = 0; i < m.count; i++) {
      if (m.kinds[i] === KIND_STATIC) {
        consider(i, [m.centers[2 * i], m.centers[2 * i + 1]]);
      } else if (m.kinds[i] === KIND_KINEMATIC) {
        consider(i, m.position(0, i, step));
      } else {
        m.engines.forEach((e, k) => { if (this.shown[k]) consider(i, m.position(k, i, step)); });
      }
    }
    return best;
  }
}
