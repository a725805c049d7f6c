// SPDX-License-Identifier: MIT
// Number and text formatting shared by the panels, the tooltip and the charts.

// A length or other figure in metres with `digits` significant digits: "0.0123", "1.2e-7", "0".
function formatNumber(v, digits) {
  if (v === null || v === undefined || Number.isNaN(v)) return "-";
  if (!Number.isFinite(v)) return v > 0 ? "inf" : "-inf";
  if (v === 0) return "0";
  const a = Math.abs(v);
  if (a >= 1e-3 && a < 1e6) return String(Number(v.toPrecision(digits || 4)));
  return v.toExponential(Math.max(0, (digits || 4) - 1)).replace("e+", "e");
}

// A coordinate precise enough to tell two engines apart: every digit down to the quantum the
// page stores positions in, and at least four significant ones.
function formatCoordinate(v, quantum) {
  if (v === null || !Number.isFinite(v)) return "lost";
  const decimals = Math.min(12, Math.max(0, Math.ceil(-Math.log10(quantum))));
  const fixed = v.toFixed(decimals);
  return Math.abs(v) >= 1e-3 || v === 0 ? fixed : formatNumber(v, 4);
}

function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, function (c) {
    return { "&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;", "'": "&#39;" }[c];
  });
}

// "steps 3-5, 9" from a sorted list of steps; past eight runs, "... (N steps in all)".
function formatSteps(steps) {
  const parts = [];
  for (let i = 0; i < steps.length; ) {
    let j = i;
    while (j + 1 < steps.length && steps[j + 1] === steps[j] + 1) j++;
    parts.push(j > i ? steps[i] + "-" + steps[j] : String(steps[i]));
    i = j + 1;
  }
  const shown = parts.length > 8 ? parts.slice(0, 8).join(", ") + ", ... (" + steps.length +
                                       " steps in all)"
                                 : parts.join(", ");
  return (steps.length > 1 ? "steps " : "step ") + shown;
}
