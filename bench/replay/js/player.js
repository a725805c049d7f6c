// SPDX-License-Identifier: MIT
// Plays the steps at the simulation's own pace (one step every dt seconds) times a speed, on the
// browser's animation frames, skipping steps when drawing cannot keep up rather than slowing
// down. Keeps the time each frame took to draw and the gaps between frames, for window.replay.

const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4, 8, 16, 32];

class Player {
  // show(step) draws a step and returns nothing; called on every change of step.
  constructor(model, show, onState) {
    this.model = model;
    this.show = show;
    this.onState = onState;  // called when playing starts or stops
    this.step = 0;
    this.playing = false;
    this.speed = 1;
    this.resetStats();
  }

  resetStats() {
    this.draws = [];      // ms each frame took to draw
    this.intervals = [];  // ms between animation frames while playing
  }

  seek(step) {
    const clamped = Math.max(0, Math.min(this.model.steps, Math.round(step)));
    this.step = clamped;
    const t0 = performance.now();
    this.show(clamped);
    this.draws.push(performance.now() - t0);
    if (this.playing) this.anchor(performance.now());
  }

  setSpeed(speed) {
    this.speed = speed;
    if (this.playing) this.anchor(performance.now());
  }

  // Steps are counted from here: the current step at this moment.
  anchor(now) {
    this.startTime = now;
    this.startStep = this.step;
  }

  play() {
    if (this.playing) return;
    if (this.step >= this.model.steps) this.seek(0);
    this.playing = true;
    this.lastFrame = null;
    this.anchor(performance.now());
    this.onState(true);
    requestAnimationFrame((now) => this.tick(now));
  }

  pause() {
    if (!this.playing) return;
    this.playing = false;
    this.onState(false);
  }

  toggle() {
    if (this.playing) this.pause(); else this.play();
  }

  tick(now) {
    if (!this.playing) return;
    if (this.lastFrame !== null) this.intervals.push(now - this.lastFrame);
    this.lastFrame = now;
    const elapsed = Math.max(0, now - this.startTime) / 1000;
    const target = this.startStep + Math.floor(elapsed * this.speed / this.model.dt);
    if (target >= this.model.steps) {
      this.playing = false;  // so that seek() does not re-anchor
      this.seek(this.model.steps);
      this.onState(false);
      return;
    }
    if (target !== this.step) {
      const start = this.startTime, from = this.startStep;
      this.seek(target);
      this.startTime = start;  // keep the pace of the whole run, not of this frame
      this.startStep = from;
    }
    requestAnimationFrame((t) => this.tick(t));
  }

  // {frames, draw_ms: {mean, p95, max}, interval_ms: {mean, p95, max}} since the last reset.
  stats() {
    const summary = (values) => {
      if (!values.length) return { mean: 0, p95: 0, max: 0 };
      const sorted = values.slice().sort((a, b) => a - b);
      return { mean: sorted.reduce((a, b) => a + b, 0) / sorted.length,
               p95: sorted[Math.min(sorted.length - 1, Math.ceil(0.95 * sorted.length) - 1)],
               max: sorted[sorted.length - 1] };
    };
    return { frames: this.draws.length, draw_ms: summary(this.draws),
             interval_ms: summary(this.intervals) };
  }
}
