// whitted view: layers, tone maps (the CLI's operators, same numbers), a pixel probe,
// relighting from light layers (the same sum as `whitted relight`), A/B with a reference.
"use strict";

const token = new URLSearchParams(location.search).get("token");
const api = (path) => `${path}${path.includes("?") ? "&" : "?"}token=${token}`;

const state = {
  meta: null,
  layers: {}, // name -> Float32Array (pixel-major, the layer's channels)
  reference: null, // beauty of the reference, Float32Array RGBA
  selected: "beauty",
  gains: {}, // light -> [r, g, b]
  shadows: {}, // light -> true when shown with shadows
  ambient: 1,
  background: 1,
  display: null, // Uint8ClampedArray RGBA of the canvas
  ranges: {}, // name -> [lo, hi] of a data layer's values, for showing it
  pending: {}, // name -> the fetch of that layer under way, so it is fetched once
  step: 1, // pixels of the image per pixel of the canvas
  generation: 0, // of the latest draw: an older draw that finishes late is dropped
};

// ---- tone maps: docs/tonemap.md, as src/tonemap.rs evaluates them ----
const MAX_INPUT = 1e9;
const srgb = (t) => (t <= 0.0031308 ? 12.92 * t : 1.055 * Math.pow(t, 1 / 2.4) - 0.055);
const clamp01 = (x) => Math.min(Math.max(x, 0), 1);
const mul = (m, v) => [0, 1, 2].map((r) => m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2]);
const AGX = {
  to2020: [[0.6274, 0.3293, 0.0433], [0.0691, 0.9195, 0.0113], [0.0164, 0.088, 0.8956]],
  inset: [[0.856627153315983, 0.0951212405381588, 0.0482516061458583],
    [0.137318972929847, 0.761241990602591, 0.101439036467562],
    [0.11189821299995, 0.0767994186031903, 0.811302368396859]],
  outset: [[1.1271005818144368, -0.1106066430966032, -0.0164939387178346],
    [-0.1413297634984383, 1.157823702216272, -0.0164939387178343],
    [-0.1413297634984383, -0.1106066430966029, 1.2519364065950405]],
  to709: [[1.6605, -0.5876, -0.0728], [-0.1246, 1.1329, -0.0083], [-0.0182, -0.1006, 1.1187]],
};
function agx(v) {
  const c = mul(AGX.inset, mul(AGX.to2020, v));
  const curve = c.map((x) => {
    const t = clamp01((Math.log2(Math.max(x, 1e-10)) + 12.47393) / (4.026069 + 12.47393));
    const x2 = t * t, x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * t + 31.96 * x4 - 6.868 * x2 * t + 0.4298 * x2 + 0.1191 * t - 0.00232;
  });
  const lin = mul(AGX.outset, curve).map((x) => Math.pow(Math.max(x, 0), 2.2));
  return mul(AGX.to709, lin).map(clamp01);
}
const AGX_OUT = new Float64Array(3);
/** agx() on scalars, into `out`, evaluated in the same order. */
function agxInto(r, g, b, out) {
  const m = AGX.to2020, i = AGX.inset, o = AGX.outset, t = AGX.to709;
  const r1 = m[0][0] * r + m[0][1] * g + m[0][2] * b;
  const g1 = m[1][0] * r + m[1][1] * g + m[1][2] * b;
  const b1 = m[2][0] * r + m[2][1] * g + m[2][2] * b;
  const r2 = i[0][0] * r1 + i[0][1] * g1 + i[0][2] * b1;
  const g2 = i[1][0] * r1 + i[1][1] * g1 + i[1][2] * b1;
  const b2 = i[2][0] * r1 + i[2][1] * g1 + i[2][2] * b1;
  const curve = (x) => {
    const u = clamp01((Math.log2(Math.max(x, 1e-10)) + 12.47393) / (4.026069 + 12.47393));
    const u2 = u * u, u4 = u2 * u2;
    return 15.5 * u4 * u2 - 40.14 * u4 * u + 31.96 * u4 - 6.868 * u2 * u + 0.4298 * u2 + 0.1191 * u - 0.00232;
  };
  const r3 = curve(r2), g3 = curve(g2), b3 = curve(b2);
  const lin = (x) => Math.pow(Math.max(x, 0), 2.2);
  const r4 = lin(o[0][0] * r3 + o[0][1] * g3 + o[0][2] * b3);
  const g4 = lin(o[1][0] * r3 + o[1][1] * g3 + o[1][2] * b3);
  const b4 = lin(o[2][0] * r3 + o[2][1] * g3 + o[2][2] * b3);
  out[0] = clamp01(t[0][0] * r4 + t[0][1] * g4 + t[0][2] * b4);
  out[1] = clamp01(t[1][0] * r4 + t[1][1] * g4 + t[1][2] * b4);
  out[2] = clamp01(t[2][0] * r4 + t[2][1] * g4 + t[2][2] * b4);
}

function neutral(v) {
  const x = Math.min(v[0], v[1], v[2]);
  const offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  let c = v.map((e) => e - offset);
  const peak = Math.max(c[0], c[1], c[2]);
  if (peak < 0.76) return c;
  const d = 0.24;
  const newPeak = 1 - (d * d) / (peak + d - 0.76);
  c = c.map((e) => e * (newPeak / peak));
  const g = 1 - 1 / (0.15 * (peak - newPeak) + 1);
  return c.map((e) => e * (1 - g) + newPeak * g);
}
const OPERATORS = {
  tick: (v) => v.map(clamp01),
  clamp: (v) => v.map(clamp01),
  reinhard: (v) => v.map((x) => x / (1 + x)),
  aces: (v) => v.map((x) => clamp01((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14))),
  agx,
  neutral,
};
/** Linear RGB -> three bytes, exactly as the PNG writer quantises. */
function toBytes(rgb, op, ev) {
  const scale = Math.pow(2, ev);
  const v = rgb.map((x) => (Number.isNaN(x) ? 0 : Math.min(Math.max(x * scale, 0), MAX_INPUT)));
  const t = OPERATORS[op](v);
  if (op === "tick") return t.map((x) => Math.floor(255 * x));
  return t.map((x) => Math.min(255, Math.max(0, Math.floor(255 * srgb(x) + 0.5))));
}

/** The per-channel operators as one scalar function, for the fast path of a whole image. */
const SCALAR = {
  tick: clamp01,
  clamp: clamp01,
  reinhard: (x) => x / (1 + x),
  aces: (x) => clamp01((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)),
};

/** Writes the display bytes of linear (r, g, b) into `out` at `o`, quantised exactly as the PNG
 * writer does (a lookup table would not be exact). */
function quantise(r, g, b, op, ev, scale, out, o) {
  const f = SCALAR[op];
  if (op === "agx") {
    // The same arithmetic as agx(), on scalars: no allocation per pixel.
    const bound = (x) => (Number.isNaN(x) ? 0 : Math.min(Math.max(x * scale, 0), MAX_INPUT));
    agxInto(bound(r), bound(g), bound(b), AGX_OUT);
    for (let c = 0; c < 3; c++) out[o + c] = Math.min(255, Math.max(0, Math.floor(255 * srgb(AGX_OUT[c]) + 0.5)));
    return;
  }
  if (!f) {
    const bytes = toBytes([r, g, b], op, ev);
    out[o] = bytes[0]; out[o + 1] = bytes[1]; out[o + 2] = bytes[2];
    return;
  }
  const v = [r, g, b];
  for (let c = 0; c < 3; c++) {
    const x = v[c];
    const t = f(Number.isNaN(x) ? 0 : Math.min(Math.max(x * scale, 0), MAX_INPUT));
    out[o + c] = op === "tick" ? Math.floor(255 * t) : Math.min(255, Math.max(0, Math.floor(255 * srgb(t) + 0.5)));
  }
}

// ---- data ----
async function layer(name, which = "main", step = 1) {
  const response = await fetch(api(`/api/layer?name=${encodeURIComponent(name)}&which=${which}&step=${step}`));
  if (!response.ok) throw new Error(`layer ${name}: ${response.status}`);
  return new Float32Array(await response.arrayBuffer());
}
const info = (name) => state.meta.layers.find((l) => l.name === name);

/** Fetches the layers not yet here (whole), with the range data layers are shown over; a
 * layer already being fetched (by an earlier draw) is waited for, not fetched again. */
async function need(names) {
  const fetches = names.filter((name) => !state.layers[name] && info(name)).map((name) => {
    state.pending[name] ||= layer(name).then((data) => {
      let lo = Infinity, hi = -Infinity;
      for (const x of data) if (x !== 0 && Number.isFinite(x) && x < 1e10) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
      state.ranges[name] = [lo, hi];
      state.layers[name] = data;
    }).finally(() => { delete state.pending[name]; });
    return state.pending[name];
  });
  await Promise.all(fetches);
}

/** Linear RGB of a colour layer at pixel p. */
function rgbAt(name, p) {
  const l = info(name), data = state.layers[name], n = l.channels.length;
  const at = (c) => data[p * n + l.channels.indexOf(c)];
  return [at("R"), at("G"), at("B")];
}

/** The layers and gains of the relit image, in the order of the sum. */
function relightTerms() {
  const terms = [["ambient", [state.ambient, state.ambient, state.ambient]]];
  for (const light of state.meta.lights) {
    const name = state.shadows[light] === false ? `unshadowed_${light}` : `light_${light}`;
    terms.push([name, state.gains[light] || [1, 1, 1]]);
  }
  terms.push(["background", [state.background, state.background, state.background]]);
  return terms;
}

const relighting = () =>
  state.ambient !== 1 || state.background !== 1 ||
  state.meta.lights.some((l) => (state.gains[l] || [1, 1, 1]).some((g) => g !== 1) || state.shadows[l] === false);

/** Display bytes of value q of `data`, a layer described by `l` (whole or subsampled). */
function layerBytes(l, data, q, op, ev, range) {
  const n = l.channels.length;
  if (l.role === "colour") {
    const at = (c) => data[q * n + l.channels.indexOf(c)];
    return toBytes([at("R"), at("G"), at("B")], op, ev);
  }
  const p = q;
  if (l.role === "normal") return [0, 1, 2].map((c) => Math.round(255 * clamp01((data[p * n + c] + 1) / 2)));
  if (l.role === "mask") return [0, 0, 0].map(() => Math.round(255 * clamp01(data[p * n])));
  if (l.role === "id") {
    const id = data[p * n];
    if (!(id > 0)) return [0, 0, 0];
    const hue = (id * 0.618033988749895) % 1;
    return [0, 1 / 3, 2 / 3].map((o) => Math.round(255 * (0.35 + 0.55 * (0.5 + 0.5 * Math.cos(2 * Math.PI * (hue + o))))));
  }
  return [0, 1, 2].map((c) => {
    const x = data[p * n + Math.min(c, n - 1)];
    if (!(x !== 0 && Number.isFinite(x) && x < 1e10)) return 0;
    return Math.round(255 * (0.2 + (0.8 * (x - range[0])) / Math.max(range[1] - range[0], 1e-30)));
  });
}

// ---- drawing ----
/** Draws the current view. While interacting it computes one pixel per screen pixel (every
 * step-th pixel of a large image, so a 4K render stays responsive); `full` computes every
 * pixel (for saving, and for `pixels()`). */
async function draw(full = false) {
  const generation = ++state.generation;
  const mode = document.getElementById("ab").value;
  const wanted = mode === "a" || !state.reference ? [state.selected] : ["beauty"];
  if (state.selected === "beauty" && relighting()) wanted.push(...relightTerms().map(([n]) => n));
  await need(wanted);
  // A newer draw was asked for while this one waited for its layers: it draws instead.
  if (generation !== state.generation) return;
  const { width: fullWidth, height: fullHeight } = state.meta;
  const shown = document.getElementById("view").clientWidth || fullWidth;
  const step = full ? 1 : Math.max(1, Math.floor(fullWidth / Math.max(shown, 1)));
  const width = Math.floor(fullWidth / step), height = Math.floor(fullHeight / step);
  state.step = step;
  const source = (q) => Math.floor(q / width) * step * fullWidth + (q % width) * step;
  const canvas = document.getElementById("canvas");
  canvas.width = width;
  canvas.height = height;
  const ctx = canvas.getContext("2d");
  const img = ctx.createImageData(width, height);
  const op = document.getElementById("tonemap").value;
  const ev = Number(document.getElementById("exposure").value);
  const l = info(state.selected);
  if ((mode === "a" || !state.reference) && l.role === "colour") {
    // The fast path for colour layers and the relit beauty: no allocation per pixel.
    const scale = Math.pow(2, ev);
    const terms = state.selected === "beauty" && relighting() ? relightTerms() : [[state.selected, [1, 1, 1]]];
    const planes = terms.map(([name, gain]) => {
      const li = info(name), n = li.channels.length;
      return [state.layers[name], n, li.channels.indexOf("R"), li.channels.indexOf("G"), li.channels.indexOf("B"), gain];
    });
    for (let q = 0; q < width * height; q++) {
      const p = source(q);
      let r = 0, g = 0, b = 0;
      for (const [data, n, ri, gi, bi, gain] of planes) {
        r += data[p * n + ri] * gain[0];
        g += data[p * n + gi] * gain[1];
        b += data[p * n + bi] * gain[2];
      }
      quantise(r, g, b, op, ev, scale, img.data, q * 4);
      img.data[q * 4 + 3] = 255;
    }
    finishDraw(ctx, img, op, ev);
    return;
  }
  for (let q = 0; q < width * height; q++) {
    const p = source(q);
    let bytes;
    if (mode === "a" || !state.reference) {
      bytes = layerBytes(l, state.layers[state.selected], p, op, ev, state.ranges[state.selected]);
    } else {
      const b = [0, 1, 2].map((c) => state.reference[p * 4 + c]);
      if (mode === "b") bytes = toBytes(b, op, ev);
      else {
        const a = rgbAt("beauty", p);
        const e = Math.max(...[0, 1, 2].map((c) => Math.abs(a[c] - b[c])));
        const t = e === 0 ? 0 : clamp01((Math.log10(e) + 6) / 6);
        bytes = e === 0 ? [0, 0, 0] : [Math.round(255 * t), Math.round(255 * t * t), Math.round(90 * (1 - t))];
      }
    }
    img.data.set([bytes[0], bytes[1], bytes[2], 255], q * 4);
  }
  finishDraw(ctx, img, op, ev);
}

function finishDraw(ctx, img, op, ev) {
  ctx.putImageData(img, 0, 0);
  state.display = img.data;
  document.getElementById("status").textContent =
    `${state.selected}${state.selected === "beauty" && relighting() ? " (relit)" : ""}, ${op}, EV ${ev.toFixed(1)}`;
}

async function thumbnails() {
  const nav = document.getElementById("layers");
  nav.textContent = "";
  const groups = { beauty: [], effects: [], lights: [], bounces: [], masks: [], data: [] };
  for (const l of state.meta.layers) {
    const g = l.name === "beauty" ? "beauty"
      : l.name.startsWith("light_") || l.name.startsWith("unshadowed_") ? "lights"
      : l.name.startsWith("reflected") ? "bounces"
      : l.role === "mask" ? "masks" : l.role === "colour" ? "effects" : "data";
    groups[g].push(l.name);
  }
  const { width, height } = state.meta;
  const step = Math.max(1, Math.ceil(width / 180));
  for (const [group, names] of Object.entries(groups)) {
    if (!names.length) continue;
    const h = document.createElement("h3");
    h.textContent = group;
    nav.append(h);
    for (const name of names) {
      const fig = document.createElement("figure");
      fig.dataset.layer = name;
      if (name === state.selected) fig.className = "selected";
      const c = document.createElement("canvas");
      c.width = Math.floor(width / step);
      c.height = Math.floor(height / step);
      const ctx = c.getContext("2d");
      // One layer that cannot be had (a 404, a 503 under a tight memory limit) costs its
      // thumbnail only: the others, and the controls, go on working.
      try {
        const img = ctx.createImageData(c.width, c.height);
        const small = await layer(name, "main", step);
        let lo = Infinity, hi = -Infinity;
        for (const x of small) if (x !== 0 && Number.isFinite(x) && x < 1e10) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
        for (let q = 0; q < c.width * c.height; q++) {
          const b = layerBytes(info(name), small, q, "clamp", 0, [lo, hi]);
          img.data.set([b[0], b[1], b[2], 255], q * 4);
        }
        ctx.putImageData(img, 0, 0);
      } catch (e) {
        fig.title = e.message;
        fig.classList.add("unavailable");
      }
      const cap = document.createElement("figcaption");
      cap.textContent = name;
      fig.append(c, cap);
      fig.onclick = () => select(name);
      nav.append(fig);
    }
  }
}

function select(name) {
  state.selected = name;
  for (const f of document.querySelectorAll("nav figure")) f.className = f.dataset.layer === name ? "selected" : "";
  draw();
}

// ---- probe ----
async function probe(x, y) {
  const values = await (await fetch(api(`/api/pixel?x=${x}&y=${y}`))).json();
  const sum = [0, 0, 0];
  for (const [name, gain] of relightTerms()) {
    const v = values[name] || [0, 0, 0];
    for (let c = 0; c < 3; c++) sum[c] += v[c] * gain[c];
  }
  const text = [`pixel (${x}, ${y})`, `RGB = ambient + sum light + background = ${sum.map((v) => v.toPrecision(6)).join(", ")}`];
  for (const [name, v] of Object.entries(values)) text.push(`${name}: ${v.map((e) => e.toPrecision(6)).join(", ")}`);
  document.getElementById("probe").textContent = text.join("\n");
  return { pixel: [x, y], values, breakdown: sum };
}

// ---- relight panel ----
function hexToGain(hex, scale) {
  return [1, 3, 5].map((i) => (parseInt(hex.slice(i, i + 2), 16) / 255) * scale);
}
function relightPanel() {
  const panel = document.getElementById("relight");
  panel.textContent = "";
  const row = (label, value, onInput, colour) => {
    const div = document.createElement("div");
    div.className = "light";
    const slider = Object.assign(document.createElement("input"), { type: "range", min: 0, max: 4, step: 0.01, value });
    const out = document.createElement("output");
    out.textContent = Number(value).toFixed(2);
    div.append(`${label} `, slider, out);
    let picker = null;
    if (colour) {
      picker = Object.assign(document.createElement("input"), { type: "color", value: "#ffffff" });
      div.append(picker);
    }
    const update = () => { out.textContent = Number(slider.value).toFixed(2); onInput(Number(slider.value), picker && picker.value); };
    slider.oninput = update;
    if (picker) picker.oninput = update;
    panel.append(div);
    return div;
  };
  for (const light of state.meta.lights) {
    const div = row(`light ${light}`, 1, (g, colour) => { state.gains[light] = hexToGain(colour, g); draw(); }, true);
    const box = Object.assign(document.createElement("input"), { type: "checkbox", checked: true });
    box.onchange = () => { state.shadows[light] = box.checked; draw(); };
    div.append(" shadows ", box);
  }
  if (info("ambient")) row("ambient", 1, (g) => { state.ambient = g; draw(); });
  if (info("background")) row("background", 1, (g) => { state.background = g; draw(); });
}

// ---- start ----
async function start() {
  state.meta = await (await fetch(api("/api/image"))).json();
  if (state.meta.reference) {
    const ref = await layer("beauty", "reference");
    // The reference's own channel count (the server refuses one with other layers).
    const n = ref.length / (state.meta.width * state.meta.height);
    state.reference = new Float32Array(state.meta.width * state.meta.height * 4);
    for (let p = 0; p < state.meta.width * state.meta.height; p++)
      for (let c = 0; c < 3; c++) state.reference[p * 4 + c] = ref[p * n + c];
    document.getElementById("ab-label").hidden = false;
  }
  if (!info("beauty")) state.selected = state.meta.layers[0].name;
  relightPanel();
  for (const id of ["tonemap", "ab"]) document.getElementById(id).onchange = draw;
  document.getElementById("exposure").oninput = (e) => {
    document.getElementById("exposure-value").textContent = Number(e.target.value).toFixed(1);
    draw();
  };
  document.getElementById("canvas").onclick = (e) => {
    const c = e.target, r = c.getBoundingClientRect();
    const step = state.step || 1;
    probe(step * Math.floor(((e.clientX - r.left) * c.width) / r.width), step * Math.floor(((e.clientY - r.top) * c.height) / r.height));
  };
  document.getElementById("reset").onclick = () => {
    Object.assign(state, { gains: {}, shadows: {}, ambient: 1, background: 1 });
    relightPanel();
    draw();
  };
  document.getElementById("save").onclick = async () => {
    await draw(true);
    document.getElementById("canvas").toBlob((blob) => {
      const a = Object.assign(document.createElement("a"), { href: URL.createObjectURL(blob), download: `${state.selected}.png` });
      a.click();
    });
  };
  // The controls are wired first: a layer that fails to load below leaves them working.
  await draw().catch((e) => { document.getElementById("status").textContent = `error: ${e.message}`; });
  await thumbnails();
  window.whitted.ready = true;
}

// What the browser tests (and a curious user's console) drive: the same functions the
// controls call.
window.whitted = {
  ready: false,
  probe,
  setGain(light, r, g, b) { state.gains[light] = [r, g, b]; return draw(); },
  setShadows(light, on) { state.shadows[light] = on; return draw(); },
  setToneMap(op, ev) { document.getElementById("tonemap").value = op; document.getElementById("exposure").value = ev; return draw(); },
  async pixels() { await draw(true); return Array.from(state.display); },
};
start().catch((e) => { document.getElementById("status").textContent = `error: ${e.message}`; });
