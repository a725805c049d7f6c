// SPDX-License-Identifier: MIT
// The charts under the scene, one panel per figure over the steps, one line per engine: the
// distance from the reference's centres (largest over the dynamic bodies), the energy-free
// displacement of each step (summed over them), the deepest overlap of any two boxes and the wall
// time of each step; all at every step in full precision. A cursor marks the current step, ticks the failed checks (red)
// and events (the engine's colour); a click or drag picks the step.

const CHART_LEFT = 70, CHART_RIGHT = 14, CHART_TITLE = 15, CHART_AXIS = 18;

class Chart {
  constructor(canvas, model, marks, onSeek) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.model = model;
    this.marks = marks;
    this.log = false;
    this.shown = model.engines.map(() => true);
    const ref = model.reference !== null ? model.engines[model.reference].label : null;
    this.panels = [];
    if (ref !== null) {
      this.panels.push({ key: "error_max", skip: model.reference,
                         title: "distance from " + ref + "'s centres, largest over the dynamic bodies (m)" });
    }
    this.panels.push({ key: "efd", skip: -1,
                       title: "energy-free displacement of the step, summed over the dynamic bodies (m)" });
    this.panels.push({ key: "penetration", skip: -1, title: "deepest overlap of two boxes (m)" });
    // The wall time of each step, as the run timed it: where the slow frames are, and what the
    // scene was doing then. Absent from pages written before it was recorded.
    if (model.engines.some((e) => e.series.ms)) {
      this.panels.push({ key: "ms", skip: -1, title: "wall time of the step (ms)" });
    }
    this.ticks = model.engines.map((e, k) => marks.chartSteps(k));
    this.cache = document.createElement("canvas");
    let dragging = false;
    const seek = (ev) => onSeek(this.stepAt(ev.offsetX));
    canvas.addEventListener("mousedown", (ev) => { dragging = true; seek(ev); });
    canvas.addEventListener("mousemove", (ev) => { if (dragging) seek(ev); });
    window.addEventListener("mouseup", () => { dragging = false; });
  }

  resize() {
    const ratio = window.devicePixelRatio || 1;
    this.width = this.canvas.clientWidth;
    this.height = this.canvas.clientHeight;
    for (const c of [this.canvas, this.cache]) {
      c.width = Math.max(1, Math.round(this.width * ratio));
      c.height = Math.max(1, Math.round(this.height * ratio));
    }
    this.ratio = ratio;
    this.render();
  }

  x(step) {
    const span = this.width - CHART_LEFT - CHART_RIGHT;
    return CHART_LEFT + span * step / Math.max(1, this.model.steps);
  }

  stepAt(px) {
    const span = this.width - CHART_LEFT - CHART_RIGHT;
    const step = Math.round((px - CHART_LEFT) / span * this.model.steps);
    return Math.max(0, Math.min(this.model.steps, step));
  }

  // Panel p's box: top of its plot area and its height, pixels.
  panelBox(p) {
    const h = (this.height - CHART_AXIS) / this.panels.length;
    return { top: p * h + CHART_TITLE, height: h - CHART_TITLE - 4 };
  }

  // The y range of a panel over the engines shown: [low, high], and a map to pixels.
  scale(panel, box) {
    let high = 0, lowPositive = Infinity;
    this.model.engines.forEach((e, k) => {
      if (!this.shown[k] || k === panel.skip) return;
      for (const v of e.series[panel.key] || []) {
        if (v === null || !Number.isFinite(v)) continue;
        high = Math.max(high, v);
        if (v > 0) lowPositive = Math.min(lowPositive, v);
      }
    });
    if (this.log && high > 0) {
      const top = Math.pow(10, Math.ceil(Math.log10(high)));
      const bottom = Math.max(Math.pow(10, Math.floor(Math.log10(lowPositive))), top * 1e-12);
      const span = Math.log10(top / bottom) || 1;
      return { low: bottom, high: top, log: true,
               y: (v) => box.top + box.height * (1 - Math.log10(Math.max(v, bottom) / bottom) / span) };
    }
    const top = high > 0 ? high * 1.08 : 1;
    return { low: 0, high: top, log: false, y: (v) => box.top + box.height * (1 - v / top) };
  }

  // Draws the lines, axes and ticks once into the cache; draw() adds the cursor.
  render() {
    const ctx = this.cache.getContext("2d");
    ctx.setTransform(this.ratio, 0, 0, this.ratio, 0, 0);
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, this.width, this.height);
    ctx.font = "11px system-ui, sans-serif";
    this.panels.forEach((panel, p) => {
      const box = this.panelBox(p);
      const s = this.scale(panel, box);
      panel.s = s;
      ctx.fillStyle = "#5b6470";
      ctx.textAlign = "left";
      ctx.fillText(panel.title + (s.log ? ", log scale" : ""), CHART_LEFT, box.top - 3);
      ctx.strokeStyle = "#d6dae0";
      ctx.lineWidth = 1;
      ctx.strokeRect(CHART_LEFT, box.top, this.width - CHART_LEFT - CHART_RIGHT, box.height);
      ctx.textAlign = "right";
      for (const v of s.log ? [s.low, s.high] : [0, s.high / 1.08]) {
        ctx.fillText(formatNumber(v, 3), CHART_LEFT - 4, s.y(v) + 4);
      }
      this.model.engines.forEach((e, k) => {
        if (!this.shown[k] || k === panel.skip) return;
        const values = e.series[panel.key] || [];
        ctx.strokeStyle = engineColour(k);
        ctx.lineWidth = 1.5;
        ctx.beginPath();
        let pen = false;
        values.forEach((v, step) => {
          if (v === null || !Number.isFinite(v)) { pen = false; return; }
          const x = this.x(step), y = s.y(v);
          if (pen) ctx.lineTo(x, y); else ctx.moveTo(x, y);
          pen = true;
        });
        ctx.stroke();
        const t = this.ticks[k];
        ctx.fillStyle = engineColour(k);
        for (const step of t.events) ctx.fillRect(this.x(step) - 0.5, box.top, 1, 5);
        ctx.fillStyle = FAIL_COLOUR;
        for (const step of t.failed) {
          const x = this.x(step);
          ctx.beginPath();
          ctx.moveTo(x - 4, box.top); ctx.lineTo(x + 4, box.top); ctx.lineTo(x, box.top + 7);
          ctx.fill();
        }
      });
    });
    ctx.fillStyle = "#5b6470";
    ctx.textAlign = "center";
    const last = this.model.steps;
    const every = niceLength(Math.max(1, last / 8));
    for (let step = 0; step <= last; step += every) ctx.fillText(step, this.x(step), this.height - 5);
  }

  draw(step) {
    const ctx = this.ctx;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.drawImage(this.cache, 0, 0);
    ctx.setTransform(this.ratio, 0, 0, this.ratio, 0, 0);
    const x = this.x(step);
    ctx.strokeStyle = "#000000";
    ctx.lineWidth = 1;
    ctx.beginPath();
    ctx.moveTo(x, CHART_TITLE - 2);
    ctx.lineTo(x, this.height - CHART_AXIS);
    ctx.stroke();
  }

  // The panel under canvas y, and every shown engine's value there at `step`: for the tooltip.
  valuesAt(py, step) {
    const p = this.panels.findIndex((panel, i) => {
      const box = this.panelBox(i);
      return py >= box.top - CHART_TITLE && py <= box.top + box.height;
    });
    if (p < 0) return null;
    const panel = this.panels[p];
    const rows = [];
    this.model.engines.forEach((e, k) => {
      if (this.shown[k] && k !== panel.skip)
        rows.push({ engine: k, value: (e.series[panel.key] || [])[step] });
    });
    return { title: panel.title, rows: rows };
  }
}
