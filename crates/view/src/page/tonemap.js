// ---- tone maps: docs/tonemap.md, evaluated as src/tonemap.rs evaluates them ----
// One path for every pixel the page shows (the view, the thumbnails, the saved PNG): bound
// the input, apply the operator, sRGB-encode (all but `tick` and `sigmoid`, the course's),
// quantise as the PNG writer
// does. A browser test compares it with `whitted tonemap` for every operator.
"use strict";

const TONEMAP = (() => {
  const MAX_INPUT = 1e9;
  const clamp01 = (x) => Math.min(Math.max(x, 0), 1);
  const srgb = (t) => (t <= 0.0031308 ? 12.92 * t : 1.055 * Math.pow(t, 1 / 2.4) - 0.055);
  const bound = (x) => (Number.isNaN(x) ? 0 : Math.min(Math.max(x, 0), MAX_INPUT));
  const aces = (x) => clamp01((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14));
  const TO2020 = [0.6274, 0.3293, 0.0433, 0.0691, 0.9195, 0.0113, 0.0164, 0.088, 0.8956];
  const INSET = [0.856627153315983, 0.0951212405381588, 0.0482516061458583,
    0.137318972929847, 0.761241990602591, 0.101439036467562,
    0.11189821299995, 0.0767994186031903, 0.811302368396859];
  const OUTSET = [1.1271005818144368, -0.1106066430966032, -0.0164939387178346,
    -0.1413297634984383, 1.157823702216272, -0.0164939387178343,
    -0.1413297634984383, -0.1106066430966029, 1.2519364065950405];
  const TO709 = [1.6605, -0.5876, -0.0728, -0.1246, 1.1329, -0.0083, -0.0182, -0.1006, 1.1187];
  const v = new Float64Array(3), w = new Float64Array(3);
  /** w = m * v, rows of m in order. */
  const mul = (m, from, to) => {
    const a = from[0], b = from[1], c = from[2];
    for (let r = 0; r < 3; r++) to[r] = m[3 * r] * a + m[3 * r + 1] * b + m[3 * r + 2] * c;
  };
  const curve = (x) => {
    const u = clamp01((Math.log2(Math.max(x, 1e-10)) + 12.47393) / (4.026069 + 12.47393));
    const u2 = u * u, u4 = u2 * u2;
    return 15.5 * u4 * u2 - 40.14 * u4 * u + 31.96 * u4 - 6.868 * u2 * u + 0.4298 * u2 + 0.1191 * u - 0.00232;
  };
  function agx() {
    mul(TO2020, v, w);
    mul(INSET, w, v);
    for (let c = 0; c < 3; c++) v[c] = curve(v[c]);
    mul(OUTSET, v, w);
    for (let c = 0; c < 3; c++) w[c] = Math.pow(Math.max(w[c], 0), 2.2);
    mul(TO709, w, v);
    for (let c = 0; c < 3; c++) v[c] = clamp01(v[c]);
  }
  function neutral() {
    const x = Math.min(v[0], v[1], v[2]);
    const offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    for (let c = 0; c < 3; c++) v[c] -= offset;
    const peak = Math.max(v[0], v[1], v[2]);
    if (peak < 0.76) return;
    const d = 0.24;
    const newPeak = 1 - (d * d) / (peak + d - 0.76);
    const g = 1 - 1 / (0.15 * (peak - newPeak) + 1);
    for (let c = 0; c < 3; c++) v[c] = v[c] * (newPeak / peak) * (1 - g) + newPeak * g;
  }
  /** The course's own from 2018-19 (docs/courses.md), on the exact value: NaN, infinite or
   * negative input gives 0, as the course's arithmetic does. */
  const sigmoid = (x) => {
    const p = Math.pow(x, 1.3);
    const g = Math.pow(p * (1 / (p + Math.pow(0.5 / 2, 1.3))), 1 / 2.2);
    return Number.isNaN(g) ? 0 : clamp01(g);
  };
  const OPERATORS = {
    tick() { for (let c = 0; c < 3; c++) v[c] = clamp01(v[c]); },
    clamp() { for (let c = 0; c < 3; c++) v[c] = clamp01(v[c]); },
    reinhard() { for (let c = 0; c < 3; c++) v[c] = v[c] / (1 + v[c]); },
    aces() { for (let c = 0; c < 3; c++) v[c] = aces(v[c]); },
    agx,
    neutral,
    sigmoid() { },
  };
  /** Whether an operator's display values are sRGB-encoded (not the course's two). */
  const encoded = (op) => op !== "tick" && op !== "sigmoid";
  return {
    names: Object.keys(OPERATORS),
    /** Writes the display bytes of linear (r, g, b) times `gain` (2^EV) into out[o..o+3]. */
    into(r, g, b, op, gain, out, o) {
      if (op === "sigmoid") {
        v[0] = sigmoid(r * gain); v[1] = sigmoid(g * gain); v[2] = sigmoid(b * gain);
      } else {
        v[0] = bound(r * gain); v[1] = bound(g * gain); v[2] = bound(b * gain);
        OPERATORS[op]();
      }
      for (let c = 0; c < 3; c++) {
        out[o + c] = !encoded(op)
          ? Math.floor(255 * v[c])
          : Math.min(255, Math.max(0, Math.floor(255 * srgb(v[c]) + 0.5)));
      }
    },
    clamp01,
  };
})();
