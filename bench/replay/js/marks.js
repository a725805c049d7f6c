// SPDX-License-Identifier: MIT
// What the page marks on the scene, the charts and the side panel: the scene's expectations
// (where a body should be, bounds on its centre) and, per engine, its failed checks (the
// verdict's findings, each with its bodies and step), its events (a crushed body, say) and its
// counted events, each shown for a short while after its step.

class Marks {
  constructor(model, data) {
    this.model = model;
    this.expectations = data.scene.expect.map((e, i) => this.expectation(e, i));
    this.timed = [];  // {engine, bodies, step, until, failed, short, text}
    this.items = [];  // side-panel entries: {engine, step, failed, html, bodies}
    // A failed check stays marked for half a second of simulated time, an event for a tenth,
    // and neither for more than a twentieth of the run.
    const hold = (seconds) => Math.max(1, Math.min(Math.round(seconds / model.dt),
                                                   Math.round(model.steps / 20)));
    this.failHold = hold(0.5);
    data.engines.forEach((e, k) => {
      this.addFindings(e, k, this.failHold);
      this.addEvents(e, k, hold(0.1));
      this.addCounted(e, k);
    });
    this.items.sort((a, b) => a.step - b.step || a.engine - b.engine);
    this.byStep = Array.from({ length: model.steps + 1 }, () => []);
    for (const mark of this.timed) {
      for (let s = Math.max(0, mark.step); s <= Math.min(mark.until, model.steps); s++)
        this.byStep[s].push(mark);
    }
  }

  at(step) {
    return this.byStep[Math.max(0, Math.min(step, this.model.steps))];
  }

  label(k) {
    return this.model.engines[k].label;
  }

  // An expectation entry as the scene states it (schema of bench/output/report.h's
  // expectation_json): when it applies, its targets and its bounds.
  expectation(e, index) {
    const m = this.model;
    const windowed = e.from_step !== undefined;
    const from = windowed ? e.from_step : m.steps;
    const to = windowed ? e.to_step : m.steps;
    const every = e.body === "*";
    const body = every ? -1 : m.bodyIndex(e.body);
    const who = every ? "every dynamic body" : e.body;
    const out = {
      index: index, kind: e.kind, every: every, tolerance: e.tolerance || 0,
      from: from, to: to, windowed: windowed,
      body: body,
      // A final-state entry is drawn throughout, as the target the run heads for.
      shownAt: (step) => !windowed || (step >= from && step <= to),
      checkedAt: (step) => step >= from && step <= to,
    };
    const bodies = every ? [...Array(m.count).keys()].filter((i) => m.kinds[i] === KIND_DYNAMIC)
                         : body >= 0 ? [body] : [];
    const when = windowed ? " from step " + from + " to " + to : " at the last step";
    if (e.kind === "center") {
      out.targets = [{ body: body, at: e.center }];
      out.text = who + " centred at (" + e.center.map((v) => formatNumber(v, 6)).join(", ") +
                 ") within " + formatNumber(e.tolerance) + " m" + when;
    } else if (e.kind === "moved") {
      out.targets = bodies.map((i) => ({
        body: i, at: [m.centers[2 * i] + e.moved[0], m.centers[2 * i + 1] + e.moved[1]] }));
      out.text = who + (e.moved[0] === 0 && e.moved[1] === 0 ? " stays put"
                        : " moves by (" + e.moved.map((v) => formatNumber(v, 6)).join(", ") + ")") +
                 " within " + formatNumber(e.tolerance) + " m" + when;
    } else if (e.kind === "bounds") {
      out.bounds = [];
      const names = ["x", "y"];
      [0, 1].forEach((axis) => {
        if (e.min[axis] !== null)
          out.bounds.push({ axis: axis, value: e.min[axis],
                            text: "expect[" + index + "] " + names[axis] + " >= " + formatNumber(e.min[axis], 6) });
        if (e.max[axis] !== null)
          out.bounds.push({ axis: axis, value: e.max[axis],
                            text: "expect[" + index + "] " + names[axis] + " <= " + formatNumber(e.max[axis], 6) });
      });
      out.text = who + "'s centre within " + out.bounds.map((b) => b.text.split("] ")[1]).join(", ") + when;
    } else if (e.kind === "at_rest") {
      out.text = who + " at rest (at most " + formatNumber(e.at_rest) + " m/s)" + when;
    } else {
      out.text = "no two boxes overlap deeper than " + formatNumber(e.no_overlap) + " m" + when;
    }
    out.focus = { step: windowed ? from : m.steps, bodies: body >= 0 ? [body] : [] };
    return out;
  }

  addFindings(e, k, hold) {
    if (!e.verdict) return;
    for (const f of e.verdict.findings) {
      const bodies = (f.bodies || []).slice(0, 50);
      const step = f.step === undefined || f.step < 0 ? null : f.step;
      const short = this.label(k) + ": " + f["class"];
      if (step !== null && bodies.length)
        this.timed.push({ engine: k, bodies: bodies, step: step, until: step + hold, failed: true,
                          short: short, text: f.detail });
      this.items.push({ engine: k, step: step === null ? 0 : step, failed: true, bodies: bodies,
                        html: "<span class=\"fail\">" + escapeHtml(short) + "</span> " +
                              (step === null ? "" : "<span class=\"step\">step " + step + "</span> ") +
                              escapeHtml(f.detail) });
    }
  }

  addEvents(e, k, hold) {
    const ev = e.events;
    const groups = new Map();  // "kind body" -> steps
    for (let j = 0; j < ev.step.length; j++) {
      const kind = ev.kinds[ev.kind[j]], body = ev.body[j], step = ev.step[j];
      this.timed.push({ engine: k, bodies: [body], step: step, until: step + hold, failed: false,
                        short: this.label(k) + ": " + kind, text: kind + " " + this.model.names[body] });
      const key = kind + "\u0000" + body;
      if (!groups.has(key)) groups.set(key, { kind: kind, body: body, steps: [] });
      groups.get(key).steps.push(step);
    }
    for (const g of groups.values()) {
      this.items.push({ engine: k, step: g.steps[0], failed: false, bodies: [g.body],
                        html: escapeHtml(this.label(k) + ": " + g.kind + " " +
                                         this.model.names[g.body]) +
                              " <span class=\"step\">" + formatSteps(g.steps) + "</span>" });
    }
    if (ev.left_out > 0) {
      this.items.push({ engine: k, step: this.model.steps, failed: false, bodies: [],
                        html: escapeHtml(this.label(k) + ": " + ev.left_out +
                                         " more events not stored") });
    }
  }

  addCounted(e, k) {
    // A count whose steps are those of an event kind says less than the events: left out.
    const eventSteps = new Map();
    e.events.step.forEach((step, j) => {
      const kind = e.events.kind[j];
      if (!eventSteps.has(kind)) eventSteps.set(kind, new Set());
      eventSteps.get(kind).add(step);
    });
    const sameSteps = (steps) => [...eventSteps.values()].some(
        (set) => set.size === new Set(steps).size && steps.every((s) => set.has(s)));
    for (const c of e.counted) {
      if (!c.step.length || sameSteps(c.step)) continue;
      const total = c.value.reduce((a, b) => a + b, 0);
      this.items.push({ engine: k, step: c.step[0], failed: false, bodies: [],
                        html: escapeHtml(this.label(k) + ": " + c.name + " " + formatNumber(total) +
                                         " (" + c.help + ")") +
                              " <span class=\"step\">" + formatSteps(c.step) + "</span>" });
    }
    if (e.degraded.length) {
      this.items.push({ engine: k, step: e.degraded[0], failed: false, bodies: [],
                        html: escapeHtml(this.label(k) + ": cut short") +
                              " <span class=\"step\">" + formatSteps(e.degraded) + "</span>" });
    }
  }

  // The steps the chart marks for engine k: failed checks, and any other event.
  chartSteps(k) {
    const failed = new Set(), events = new Set();
    for (const mark of this.timed) {
      if (mark.engine === k) (mark.failed ? failed : events).add(mark.step);
    }
    return { failed: [...failed], events: [...events] };
  }
}
