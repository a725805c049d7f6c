// SPDX-License-Identifier: MIT
// The replay's data as the views ask for it: bodies, engines and each engine's centre of every
// body at any step, from the page's JSON (written by bench/output/replay_page.cpp).

const KIND_STATIC = 0;
const KIND_KINEMATIC = 1;
const KIND_DYNAMIC = 2;

class ReplayModel {
  constructor(data) {
    const scene = data.scene;
    this.scene = scene;
    this.steps = scene.steps;
    this.dt = scene.dt;
    this.count = scene.bodies;
    this.names = scene.names;
    this.quantum = data.quantum;
    this.stride = data.stride;
    this.reference = data.reference;  // an engine index, or null
    const codes = { static: KIND_STATIC, kinematic: KIND_KINEMATIC, dynamic: KIND_DYNAMIC };
    this.kinds = Uint8Array.from(scene.kinds, (k) => codes[k]);
    this.half = Float64Array.from(scene.half_extents);
    this.centers = Float64Array.from(scene.centers);
    this.byName = new Map(this.names.map((name, i) => [name, i]));
    // Bodies that come and go: body i is in the world in states from[i]..to[i] (to null: to the
    // end). Absent from the data when every body is there throughout.
    const lives = scene.lives;
    this.from = lives ? Int32Array.from(lives.from) : null;
    this.to = lives ? Float64Array.from(lives.to, (t) => (t === null ? Infinity : t)) : null;
    this.engines = data.engines.map((e) => this.loadEngine(e));
    // Bodies no engine ever moves: stored once, as built.
    this.resting = 0;
    for (let i = 0; i < this.count; i++) {
      if (this.engines.every((e) => e.track.slot[i] < 0)) this.resting++;
    }
  }

  loadEngine(e) {
    const final = new Map();  // body -> exact final centre (null if lost), bodies that moved
    e.final.bodies.forEach((body, k) => {
      const x = e.final.xy[2 * k];
      const y = e.final.xy[2 * k + 1];
      final.set(body, x === null || y === null ? null : [x, y]);
    });
    return Object.assign({}, e, { track: decodeTrack(e.positions, this.count), final: final });
  }

  // The stored state shown at `step`: the last one at or before it.
  stateAt(step) {
    if (step >= this.steps) return Math.ceil(this.steps / this.stride);
    return Math.floor(Math.max(0, step) / this.stride);
  }

  // Whether `step` is shown exactly as the engines computed it: as built, or after the last step.
  isExact(step) {
    return step <= 0 || step >= this.steps;
  }

  // A body's centre in an engine at a step as the page stores it: quantised, held from the last
  // stored state; null while lost (not finite, or beyond 2^50 quanta from its start).
  storedPosition(engine, body, step) {
    const track = this.engines[engine].track;
    const m = track.slot[body];
    const x0 = this.centers[2 * body];
    const y0 = this.centers[2 * body + 1];
    if (m < 0) return [x0, y0];
    const state = Math.min(this.stateAt(step), track.states - 1);
    const at = (state * track.movers.length + m) * 2;
    const dx = track.offsets[at];
    if (Number.isNaN(dx)) return null;
    return [x0 + dx * this.quantum, y0 + track.offsets[at + 1] * this.quantum];
  }

  // Whether a body is in the world at a step (drawn, hovered, listed only then).
  alive(body, step) {
    const k = Math.max(0, Math.min(step, this.steps));
    return !this.from || (this.from[body] <= k && k <= this.to[body]);
  }

  // The centre the page draws: exact as built and after the last step, stored in between; null
  // while the body is lost or not in the world.
  position(engine, body, step) {
    if (!this.alive(body, step)) return null;
    if (step <= 0) return [this.centers[2 * body], this.centers[2 * body + 1]];
    if (step >= this.steps) {
      const final = this.engines[engine].final;
      return final.has(body) ? final.get(body) : [this.centers[2 * body], this.centers[2 * body + 1]];
    }
    return this.storedPosition(engine, body, step);
  }

  // An engine by index, label or full spec; -1 when there is none.
  engineIndex(engine) {
    if (typeof engine === "number") return engine >= 0 && engine < this.engines.length ? engine : -1;
    return this.engines.findIndex((e) => e.label === engine || e.spec === engine);
  }

  // A body by index or name; -1 when there is none.
  bodyIndex(body) {
    if (typeof body === "number") return body >= 0 && body < this.count ? body : -1;
    return this.byName.has(body) ? this.byName.get(body) : -1;
  }

  // What "fit" shows: every body that can move, as built and at its final centres, and every
  // static body, a side longer than three times theirs cut to a band around them (a floor 1 km
  // wide shows as wide as they are, plus as much on each side); every body when none can move.
  extent() {
    const box = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };
    const grow = (x0, y0, x1, y1) => {
      if (![x0, y0, x1, y1].every(Number.isFinite) || x0 > x1 || y0 > y1) return;
      box.x0 = Math.min(box.x0, x0); box.y0 = Math.min(box.y0, y0);
      box.x1 = Math.max(box.x1, x1); box.y1 = Math.max(box.y1, y1);
    };
    const growBody = (i, p) => {
      if (p) grow(p[0] - this.half[2 * i], p[1] - this.half[2 * i + 1],
                  p[0] + this.half[2 * i], p[1] + this.half[2 * i + 1]);
    };
    for (let i = 0; i < this.count; i++) {
      if (this.kinds[i] === KIND_STATIC) continue;
      growBody(i, this.position(0, i, 0));
      this.engines.forEach((e, k) => growBody(i, this.position(k, i, this.steps)));
    }
    if (!Number.isFinite(box.x0)) {
      for (let i = 0; i < this.count; i++) growBody(i, this.position(0, i, 0));
      return Number.isFinite(box.x0) ? box : { x0: -1, y0: -1, x1: 1, y1: 1 };
    }
    const moving = Object.assign({}, box);
    const w = moving.x1 - moving.x0, h = moving.y1 - moving.y0;
    const cut = (lo, hi, a, b, size) => hi - lo > 3 * size ? [Math.max(lo, a - size), Math.min(hi, b + size)]
                                                           : [lo, hi];
    for (let i = 0; i < this.count; i++) {
      if (this.kinds[i] !== KIND_STATIC) continue;
      const x = this.centers[2 * i], y = this.centers[2 * i + 1];
      const hx = this.half[2 * i], hy = this.half[2 * i + 1];
      const [sx0, sx1] = cut(x - hx, x + hx, moving.x0, moving.x1, w);
      const [sy0, sy1] = cut(y - hy, y + hy, moving.y0, moving.y1, h);
      grow(sx0, sy0, sx1, sy1);
    }
    return box;
  }
}
