// SPDX-License-Identifier: MIT
// Builds the page from its data, wires the controls, and exposes window.replay: the handle a
// user's console or a test (tests/browser/) drives the page with.

const data = JSON.parse(document.getElementById("replay-data").textContent);
const model = new ReplayModel(data);
const marks = new Marks(model, data);
const camera = new Camera();
const stage = document.getElementById("stage");
const view = new SceneView(document.getElementById("view"), model, camera, marks);
const slider = document.getElementById("slider");
const readout = document.getElementById("readout");
const playButton = document.getElementById("play");
const tooltip = document.getElementById("tooltip");
const chartTip = document.getElementById("chart-tip");
let hover = null;  // the body under the pointer
let player = null;
const chart = new Chart(document.getElementById("chart"), model, marks, (step) => player.seek(step));
let eventRows = [];

function show(step) {
  view.draw(step, hover);
  chart.draw(step);
  slider.value = step;
  readout.textContent = "step " + step + " / " + model.steps + "  (t = " +
      (step * model.dt).toFixed(3) + " s)";
  if (eventRows.length <= 500) {
    for (const row of eventRows) {
      const now = step >= row.item.step && step <= row.item.step + marks.failHold;
      row.li.classList.toggle("now", now);
    }
  }
  if (hover !== null && !tooltip.hidden) tooltip.innerHTML = bodyTooltip(model, view.shown, hover, step);
}

function redraw() {
  view.draw(player.step, hover);
  chart.draw(player.step);
}

player = new Player(model, show, (playing) => {
  playButton.innerHTML = playing ? "&#10074;&#10074;" : "&#9654;";
});

// Seeks to a step and brings bodies (of an engine, else the first) into view.
function focusOn(step, bodies, engine) {
  player.pause();
  player.seek(step);
  if (!bodies || !bodies.length) return;
  const k = engine === undefined ? 0 : engine;
  const p = model.position(k, bodies[0], step);
  if (!p) return;
  camera.cx = p[0];
  camera.cy = p[1];
  const size = 2 * Math.max(model.half[2 * bodies[0]], model.half[2 * bodies[0] + 1]);
  if (size * camera.scale < 30) camera.scale = 60 / size;
  redraw();
}

function setUp() {
  document.title = "chainbench replay: " + model.scene.name;
  document.getElementById("title").textContent = "chainbench replay: " + model.scene.name +
      " (" + model.count + " bodies, " + model.steps + " steps of " +
      formatNumber(model.dt, 4) + " s)";
  document.getElementById("description").textContent = model.scene.description || "";
  document.getElementById("storage").textContent = describeStorage(model, data);
  slider.max = model.steps;
  const speedSelect = document.getElementById("speed");
  for (const s of SPEEDS) {
    const option = document.createElement("option");
    option.value = s;
    option.textContent = s + "x";
    option.selected = s === 1;
    speedSelect.appendChild(option);
  }
  speedSelect.addEventListener("change", () => player.setSpeed(Number(speedSelect.value)));
  buildLegend(document.getElementById("legend"), model, (k, on) => {
    view.shown[k] = chart.shown[k] = on;
    chart.render();
    redraw();
  });
  buildExpectations(document.getElementById("expectations"), marks, focusOn);
  eventRows = buildEvents(document.getElementById("events"), marks, focusOn);
  playButton.addEventListener("click", () => player.toggle());
  slider.addEventListener("input", () => { player.pause(); player.seek(Number(slider.value)); });
  document.getElementById("fit").addEventListener("click", () => { camera.fit(model.extent()); redraw(); });
  document.getElementById("log").addEventListener("change", (ev) => {
    chart.log = ev.target.checked;
    chart.render();
    redraw();
  });
  wirePointer();
  wireChartTip();
  document.addEventListener("keydown", (ev) => {
    if (ev.target.tagName === "INPUT" && ev.target.type !== "range") return;
    const jump = ev.shiftKey ? 10 : 1;
    if (ev.key === " ") player.toggle();
    else if (ev.key === "ArrowRight") { player.pause(); player.seek(player.step + jump); }
    else if (ev.key === "ArrowLeft") { player.pause(); player.seek(player.step - jump); }
    else if (ev.key === "Home") { player.pause(); player.seek(0); }
    else if (ev.key === "End") { player.pause(); player.seek(model.steps); }
    else return;
    ev.preventDefault();
  });
  window.addEventListener("resize", () => { view.resize(); chart.resize(); redraw(); });
  view.resize();
  chart.resize();
  camera.fit(model.extent());
  player.seek(0);
}

function wirePointer() {
  const canvas = view.canvas;
  let drag = null;
  canvas.addEventListener("mousedown", (ev) => {
    drag = { x: ev.clientX, y: ev.clientY };
    stage.classList.add("dragging");
  });
  window.addEventListener("mouseup", () => { drag = null; stage.classList.remove("dragging"); });
  canvas.addEventListener("mousemove", (ev) => {
    if (drag) {
      camera.pan(ev.clientX - drag.x, ev.clientY - drag.y);
      drag = { x: ev.clientX, y: ev.clientY };
      redraw();
      return;
    }
    const body = view.bodyAt(ev.offsetX, ev.offsetY, player.step);
    if (body !== hover) {
      hover = body;
      redraw();
    }
    tooltip.hidden = hover === null;
    if (hover !== null) {
      tooltip.innerHTML = bodyTooltip(model, view.shown, hover, player.step);
      const left = Math.min(ev.offsetX + 14, stage.clientWidth - tooltip.offsetWidth - 4);
      tooltip.style.left = Math.max(0, left) + "px";
      tooltip.style.top = Math.max(0, ev.offsetY - tooltip.offsetHeight - 8) + "px";
    }
  });
  canvas.addEventListener("mouseleave", () => {
    tooltip.hidden = true;
    if (hover !== null) { hover = null; redraw(); }
  });
  canvas.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    camera.zoomAt(ev.offsetX, ev.offsetY, Math.exp(-ev.deltaY * 0.0015));
    redraw();
  }, { passive: false });
  canvas.addEventListener("dblclick", () => { camera.fit(model.extent()); redraw(); });
}

function wireChartTip() {
  const canvas = chart.canvas;
  canvas.addEventListener("mousemove", (ev) => {
    const step = chart.stepAt(ev.offsetX);
    const at = chart.valuesAt(ev.offsetY, step);
    chartTip.hidden = !at;
    if (!at) return;
    chartTip.innerHTML = "step " + step + ": " + escapeHtml(at.title) + "<table>" +
        at.rows.map((r) => "<tr><td><span class=\"swatch\" style=\"border-color:" +
                           engineColour(r.engine) + ";width:8px\"></span> " +
                           escapeHtml(model.engines[r.engine].label) + "</td><td>" +
                           formatNumber(r.value, 4) + "</td></tr>").join("") + "</table>";
    chartTip.style.left = Math.min(ev.offsetX + 12, canvas.clientWidth - chartTip.offsetWidth - 4) + "px";
    chartTip.style.top = "4px";
  });
  canvas.addEventListener("mouseleave", () => { chartTip.hidden = true; });
}

// Engines by index, label or full spec; bodies by index or name. Positions in metres.
window.replay = {
  get steps() { return model.steps; },
  get step() { return player.step; },
  get playing() { return player.playing; },
  get engines() { return model.engines.map((e) => e.label); },
  get colours() { return model.engines.map((e, k) => engineColour(k)); },
  get quantum() { return model.quantum; },
  get stride() { return model.stride; },
  seek: (step) => player.seek(step),
  play: () => player.play(),
  pause: () => player.pause(),
  setSpeed: (speed) => player.setSpeed(speed),
  bodyIndex: (name) => model.bodyIndex(name),
  // The centre drawn for a body in an engine at a step (the current one by default): exact as
  // built and after the last step, stored in between; null while lost.
  positionOf(engine, body, step) {
    const k = model.engineIndex(engine), i = model.bodyIndex(body);
    if (k < 0 || i < 0) throw new Error("no engine " + engine + " or body " + body);
    return model.position(k, i, step === undefined ? player.step : step);
  },
  // The same centre as the position stream stores it (quantised) even where the page has it
  // exact: what a decoding error would show in.
  storedPositionOf(engine, body, step) {
    const k = model.engineIndex(engine), i = model.bodyIndex(body);
    if (k < 0 || i < 0) throw new Error("no engine " + engine + " or body " + body);
    return model.storedPosition(k, i, step === undefined ? player.step : step);
  },
  stats: () => player.stats(),
  resetStats: () => player.resetStats(),
  ready: false,
};

setUp();
window.replay.ready = true;
