// ---- false colour: perceptual maps for data layers and error metrics ----
"use strict";

const COLORMAP = (() => {
  const clamp01 = (x) => Math.min(Math.max(x, 0), 1);
  // Turbo, Google's polynomial approximation (Mikhailov 2019).
  function turbo(x, out, o) {
    x = clamp01(x);
    const x2 = x * x, x3 = x2 * x, x4 = x2 * x2, x5 = x4 * x;
    const r = 0.13572138 + 4.6153926 * x - 42.66032258 * x2 + 132.13108234 * x3 - 152.94239396 * x4 + 59.28637943 * x5;
    const g = 0.09140261 + 2.19418839 * x + 4.84296658 * x2 - 14.18503333 * x3 + 4.27729857 * x4 + 2.82956604 * x5;
    const b = 0.1066733 + 12.64194608 * x - 60.58204836 * x2 + 110.36276771 * x3 - 89.90310912 * x4 + 27.34824973 * x5;
    out[o] = Math.round(255 * clamp01(r)); out[o + 1] = Math.round(255 * clamp01(g)); out[o + 2] = Math.round(255 * clamp01(b));
  }
  // Viridis, a sixth-degree polynomial fit (Zucker).
  const V = [[0.2777273272234177, 0.005407344544966578, 0.3340998053353061],
    [0.1050930431085774, 1.404613529898575, 1.384590162594685],
    [-0.3308618287255563, 0.214847559468213, 0.09509516302823659],
    [-4.634230498983486, -5.799100973351585, -19.33244095627987],
    [6.228269936347081, 14.17993336680509, 56.69055260068105],
    [4.776384997670288, -13.74514537774601, -65.35303263337234],
    [-5.435455855934631, 4.645852612178535, 26.3124352495832]];
  function viridis(t, out, o) {
    t = clamp01(t);
    for (let c = 0; c < 3; c++) {
      let y = V[6][c];
      for (let k = 5; k >= 0; k--) y = V[k][c] + t * y;
      out[o + c] = Math.round(255 * clamp01(y));
    }
  }
  // An object id as a hue of its own (golden-ratio steps), 0 (no object) black.
  function categorical(id, out, o) {
    if (!(id > 0)) { out[o] = out[o + 1] = out[o + 2] = 0; return; }
    const hue = (id * 0.618033988749895) % 1;
    for (let c = 0; c < 3; c++) out[o + c] = Math.round(255 * (0.35 + 0.55 * (0.5 + 0.5 * Math.cos(2 * Math.PI * (hue + c / 3)))));
  }
  const MAPS = { turbo, viridis };
  return {
    names: Object.keys(MAPS),
    /** The colour of value x on [lo, hi] under `map`; NaN and infinities magenta, so they show. */
    into(x, lo, hi, map, out, o) {
      if (!Number.isFinite(x)) { out[o] = 255; out[o + 1] = 0; out[o + 2] = 255; return; }
      MAPS[map](hi > lo ? (x - lo) / (hi - lo) : 0.5, out, o);
    },
    categorical,
  };
})();
