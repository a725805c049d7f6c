// SPDX-License-Identifier: MIT
// The side panel (engines with their verdicts, the expectations, the events and failed checks,
// how the page stores the runs), the readout under the scene and the tooltips.

function describeStorage(model, data) {
  const q = model.quantum;
  const every = model.stride === 1 ? "every step is stored"
      : "one step in " + model.stride + " is stored (and the last); the view holds the last " +
        "stored step in between, while the charts have every step";
  return "Centres are stored as whole multiples of " + formatNumber(q, 4) + " m (" +
      formatNumber(q * 1000, 4) + " mm: 1/4096 of the smallest box edge, rounded down to a " +
      "power of two) from each body's starting centre, so a stored centre is within " +
      formatNumber(q / 2, 3) + " m of the engine's; as built and after the last step they are " +
      "exact. Each step stores only the bodies whose stored centre changed; " + every + ". " +
      model.resting + " of " + model.count + " bodies never move in any engine and are stored " +
      "once. The charts use every step at full precision. Written by " + data.generator + ".";
}

function buildLegend(list, model, onToggle) {
  list.textContent = "";
  model.engines.forEach((e, k) => {
    const li = document.createElement("li");
    const colour = engineColour(k);
    const verdict = e.verdict ? e.verdict["class"] : "-";
    const expect = e.expect ? (e.expect.pass ? "meets the expectations"
                                             : "misses the expectations by " +
                                               formatNumber(e.expect.max_error, 3) + " m")
                            : "";
    li.innerHTML = "<label><input type=\"checkbox\" checked> <span class=\"swatch\" style=\"" +
        "border-color:" + colour + ";background:rgba(" + rgbOf(colour) + ",0.15)\"></span> " +
        "<span><b>" + escapeHtml(e.label) + "</b>" + (k === model.reference ? " (reference)" : "") +
        " <span class=\"verdict" + (verdict === "ok" || verdict === "-" ? "" : " bad") + "\">" +
        escapeHtml(verdict) + "</span><br><span class=\"verdict\">" +
        formatNumber(e.ms_per_step, 3) + " ms/step" + (expect ? "; " + expect : "") +
        "</span></span></label>";
    li.title = e.spec;
    li.querySelector("input").addEventListener("change", (ev) => onToggle(k, ev.target.checked));
    list.appendChild(li);
  });
  const fixed = document.createElement("li");
  fixed.innerHTML = "<span class=\"swatch\" style=\"border-color:#9aa1ab;background:#e4e6ea\">" +
      "</span> static and kinematic bodies (drawn once)";
  list.appendChild(fixed);
}

function buildExpectations(list, marks, onPick) {
  list.textContent = "";
  if (!marks.expectations.length) {
    list.innerHTML = "<li>The scene states none.</li>";
    return;
  }
  marks.expectations.forEach((e) => {
    const li = document.createElement("li");
    li.innerHTML = "<span class=\"step\">expect[" + e.index + "]</span> " + escapeHtml(e.text);
    li.addEventListener("click", () => onPick(e.focus.step, e.focus.bodies));
    list.appendChild(li);
  });
}

function buildEvents(list, marks, onPick) {
  list.textContent = "";
  if (!marks.items.length) {
    list.innerHTML = "<li>None: every check passed and no engine reported an event.</li>";
    return [];
  }
  return marks.items.map((item) => {
    const li = document.createElement("li");
    li.innerHTML = "<span class=\"swatch\" style=\"border-color:" + engineColour(item.engine) +
                   ";width:8px\"></span> " + item.html;
    li.addEventListener("click", () => onPick(item.step, item.bodies, item.engine));
    list.appendChild(li);
    return { li: li, item: item };
  });
}

// What the tooltip says about a body at a step: its name and, per engine, its centre and the
// distance from the reference's (or the first engine's) centre.
function bodyTooltip(model, shown, body, step) {
  const kinds = ["static", "kinematic", "dynamic"];
  const rows = [];
  const base = model.reference !== null ? model.reference : 0;
  const basePosition = model.position(base, body, step);
  // Exact centres (as built, after the last step) with twelve significant digits, stored ones
  // to the quantum's digits.
  const coordinate = (v) => !model.isExact(step) ? formatCoordinate(v, model.quantum)
      : Number.isFinite(v) ? String(Number(v.toPrecision(12))) : "lost";
  model.engines.forEach((e, k) => {
    if (!shown[k]) return;
    const p = model.position(k, body, step);
    const distance = p && basePosition && k !== base
        ? formatNumber(Math.hypot(p[0] - basePosition[0], p[1] - basePosition[1]), 3) + " m" : "";
    rows.push("<tr><td><span class=\"swatch\" style=\"border-color:" + engineColour(k) +
              ";width:8px\"></span> " + escapeHtml(e.label) + "</td><td>" +
              (p ? "(" + coordinate(p[0]) + ", " + coordinate(p[1]) + ")"
                 : model.alive(body, step) ? "lost" : "not in the world") +
              "</td><td>" + distance + "</td></tr>");
  });
  const exact = model.isExact(step) ? "exact" : "stored to within " +
      formatNumber(model.quantum / 2, 3) + " m";
  return "<b>" + escapeHtml(model.names[body]) + "</b> (" + kinds[model.kinds[body]] + ", " +
         formatNumber(2 * model.half[2 * body], 4) + " x " +
         formatNumber(2 * model.half[2 * body + 1], 4) + " m)<table>" +
         "<tr><td></td><td>centre, m (" + exact + ")</td><td>from " +
         escapeHtml(model.engines[base].label) + "</td></tr>" + rows.join("") + "</table>";
}
