// SPDX-License-Identifier: MIT
// The view's mapping between world metres (y up) and canvas pixels (y down): a centre and a
// scale, changed by fitting, zooming about a point and panning.
class Camera {
  constructor() {
    this.cx = 0;
    this.cy = 0;
    this.scale = 1;  // pixels per metre
    this.width = 1;  // canvas size, pixels
    this.height = 1;
  }

  resize(width, height) {
    this.width = Math.max(1, width);
    this.height = Math.max(1, height);
  }

  // Shows the box {x0, y0, x1, y1} whole, with a margin.
  fit(box) {
    const w = Math.max(box.x1 - box.x0, 1e-9);
    const h = Math.max(box.y1 - box.y0, 1e-9);
    this.cx = 0.5 * (box.x0 + box.x1);
    this.cy = 0.5 * (box.y0 + box.y1);
    this.scale = 0.92 * Math.min(this.width / w, this.height / h);
  }

  toScreenX(x) {
    return (x - this.cx) * this.scale + 0.5 * this.width;
  }

  toScreenY(y) {
    return 0.5 * this.height - (y - this.cy) * this.scale;
  }

  toWorld(px, py) {
    return [(px - 0.5 * this.width) / this.scale + this.cx,
            (0.5 * this.height - py) / this.scale + this.cy];
  }

  // Zooms by `factor`, keeping the world point under (px, py) where it is.
  zoomAt(px, py, factor) {
    const before = this.toWorld(px, py);
    this.scale = Math.min(Math.max(this.scale * factor, 1e-9), 1e12);
    const after = this.toWorld(px, py);
    this.cx += before[0] - after[0];
    this.cy += before[1] - after[1];
  }

  pan(dxPixels, dyPixels) {
    this.cx -= dxPixels / this.scale;
    this.cy += dyPixels / this.scale;
  }

  // The world box the canvas shows.
  visible() {
    const a = this.toWorld(0, this.height);
    const b = this.toWorld(this.width, 0);
    return { x0: a[0], y0: a[1], x1: b[0], y1: b[1] };
  }
}
