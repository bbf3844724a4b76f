// ---- whitted view: the page ----
// Layers, tone maps (TONEMAP: the CLI's operators, same numbers), zoom and pan (VIEWPORT,
// TILES), the image against a reference (A/B and the server's error metrics, in false
// colour), statistics, relighting from light layers (the same sum as `whitted relight`), a
// pixel's values and ray trees, and --watch.
"use strict";

const token = new URLSearchParams(location.search).get("token");
const api = (path) => `${path}${path.includes("?") ? "&" : "?"}token=${token}`;
const $ = (id) => document.getElementById(id);

/** Canvas pixels an image pixel must cover before its values are written in it. */
const VALUE_ZOOM = 48;

const state = {
  meta: null,
  version: 0,
  selected: "beauty",
  compare: "a", // "a" the image, "b" the reference, or an error metric's name
  view: { zoom: 1, x: 0, y: 0 },
  fitted: false, // whether the view still follows the window (until the user zooms or pans)
  gains: {}, // light -> [r, g, b]
  shadows: {}, // light -> false when shown without its shadows
  ambient: 1,
  background: 1,
  stats: new Map(), // "which\0name" -> the promise of /api/stats
  display: null, // Uint8ClampedArray RGBA of the last full-resolution render (pixels())
  generation: 0, // of the latest draw: an older draw that finishes late is dropped
  trees: null, // [x, y] of the pixel whose trees are shown
};
// Every field is declared above: in strict mode, assigning one that is not throws.
Object.seal(state);

// ---- data ----
async function fetchOk(path) {
  const response = await fetch(api(path));
  if (!response.ok) throw new Error(`${path.split("?")[0]}: ${response.status} ${await response.text()}`);
  return response;
}
const getJson = async (path) => (await fetchOk(path)).json();
async function fetchTile(which, name, step, tx, ty) {
  const q = `name=${encodeURIComponent(name)}&which=${which}&step=${step}&tx=${tx}&ty=${ty}`;
  return new Float32Array(await (await fetchOk(`/api/layer?${q}`)).arrayBuffer());
}
async function wholeLayer(name, which, step) {
  const q = `name=${encodeURIComponent(name)}&which=${which}&step=${step}`;
  return new Float32Array(await (await fetchOk(`/api/layer?${q}`)).arrayBuffer());
}
const info = (name) => state.meta.layers.find((l) => l.name === name);
const isMetric = (compare) => compare !== "a" && compare !== "b";
const whichOf = (compare) => (compare === "a" ? "main" : compare === "b" ? "reference" : compare);
function stats(which, name) {
  const key = `${which}\u0000${name}`;
  if (!state.stats.has(key)) {
    const p = getJson(`/api/stats?name=${encodeURIComponent(name)}&which=${which}`);
    p.catch(() => state.stats.delete(key));
    state.stats.set(key, p);
  }
  return state.stats.get(key);
}
/** The range a layer is shown over in false colour: its finite values short of the 1e10 a
 * miss stores in Z (the server's `range`), symmetric about 0 for the signed error. */
function rangeOf(s, compare) {
  const [lo, hi] = s.range || [0, 1];
  if (compare === "error") { const m = Math.max(Math.abs(lo), Math.abs(hi)) || 1; return [-m, m]; }
  return lo < hi ? [lo, hi] : [lo, lo + 1];
}

// ---- what a pixel shows ----
const relighting = () =>
  state.ambient !== 1 || state.background !== 1 ||
  state.meta.lights.some((l) => (state.gains[l] || [1, 1, 1]).some((g) => g !== 1) || state.shadows[l] === false);

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

/** One plane of a recipe: values `which` of layer `name` (n channels a sample), the channels
 * `picks` summed with `gain` (null: 1), and the last tile `gather` read from it. */
function plane(which, name, gain, picks) {
  return Object.seal({ which, name, gain, picks, n: info(name).channels.length, tx: -1, ty: -1, step: 0, data: undefined });
}

/** What the current settings show: the planes summed into each pixel and how the sum is
 * painted. */
function recipe() {
  const l = info(state.selected);
  const which = whichOf(state.compare);
  const rgb = (li) => ["R", "G", "B"].map((c) => li.channels.indexOf(c));
  const map = $("colormap").value;
  if (l.role === "colour") {
    const terms = state.compare === "a" && state.selected === "beauty" && relighting()
      ? relightTerms() : [[state.selected, [1, 1, 1]]];
    const planes = terms.map(([name, gain]) => plane(which, name, gain, rgb(info(name))));
    const kind = isMetric(state.compare) ? "metric" : map ? "false" : "colour";
    return { planes, kind, map: map || "turbo", channels: ["R", "G", "B"] };
  }
  const picks = l.channels.map((_, i) => i);
  const kind = isMetric(state.compare) ? "metric" : map ? "false" : l.role;
  return { planes: [plane(which, l.name, null, picks)], kind, map: map || "turbo", channels: l.channels };
}

/** Paints the summed values `px` (as `recipe` picks them) into out[o..o+3]. */
function painter(r, range) {
  const op = $("tonemap").value;
  const gain = Math.pow(2, Number($("exposure").value));
  const n = r.planes[0].picks.length;
  const [lo, hi] = range;
  const mean = (px) => { let s = 0; for (let c = 0; c < n; c++) s += px[c]; return s / n; };
  switch (r.kind) {
    case "colour": return (px, out, o) => TONEMAP.into(px[0], px[1], px[2], op, gain, out, o);
    case "metric": case "false": return (px, out, o) => COLORMAP.into(mean(px), lo, hi, r.map, out, o);
    case "normal": return (px, out, o) => { for (let c = 0; c < 3; c++) out[o + c] = Math.round(255 * TONEMAP.clamp01((px[c] + 1) / 2)); };
    case "mask": return (px, out, o) => { out[o] = out[o + 1] = out[o + 2] = Math.round(255 * TONEMAP.clamp01(px[0])); };
    case "id": return (px, out, o) => COLORMAP.categorical(px[0], out, o);
    default: return (px, out, o) => {
      for (let c = 0; c < 3; c++) {
        const x = px[Math.min(c, n - 1)];
        out[o + c] = Number.isFinite(x) && Math.abs(x) < 1e10 ? Math.round(255 * TONEMAP.clamp01((x - lo) / (hi - lo))) : 0;
      }
    };
  }
}

/** Where sample (x, y) of a layer at `step` lies: tile and index in it. */
function locate(x, y, step) {
  const T = TILES.size, { width } = state.meta;
  const sx = Math.floor(x / step), sy = Math.floor(y / step);
  const tx = Math.floor(sx / T), ty = Math.floor(sy / T);
  const tw = Math.min(T, Math.ceil((width - tx * T * step) / step));
  return [tx, ty, (sy - ty * T) * tw + (sx - tx * T)];
}

/** Sums the planes at image pixel (x, y) into `px` from tiles already here; false if one is
 * missing. Each plane remembers the last tile it read (neighbouring pixels share it), so the
 * cache is asked once per tile, not once per pixel. */
function gather(r, x, y, step, px) {
  const [tx, ty, i] = locate(x, y, step);
  px.fill(0);
  for (const p of r.planes) {
    if (p.tx !== tx || p.ty !== ty || p.step !== step) {
      p.tx = tx; p.ty = ty; p.step = step;
      p.data = TILES.peek(p.which, p.name, step, tx, ty);
    }
    if (!p.data) return false;
    const data = p.data, n = p.n, picks = p.picks, gain = p.gain;
    for (let c = 0; c < picks.length; c++) px[c] += data[i * n + picks[c]] * (gain ? gain[c] : 1);
  }
  return true;
}

/** Fetches every tile of `r`'s planes that covers image rows y0..y1, columns x0..x1. */
async function needTiles(r, step, x0, y0, x1, y1) {
  const { width, height } = state.meta;
  const clampX = (x) => Math.min(Math.max(x, 0), width - 1), clampY = (y) => Math.min(Math.max(y, 0), height - 1);
  const [ax, ay] = locate(clampX(x0), clampY(y0), step), [bx, by] = locate(clampX(x1), clampY(y1), step);
  const waits = [];
  for (const p of r.planes)
    for (let ty = ay; ty <= by; ty++)
      for (let tx = ax; tx <= bx; tx++) waits.push(TILES.get(p.which, p.name, step, tx, ty, fetchTile));
  await Promise.all(waits);
}

// ---- drawing ----
/** Renders `view` into an ImageData of cw x ch (the canvas outside the image dark grey), or
 * null when draw `generation` was overtaken meanwhile (null: never overtaken). */
async function render(view, cw, ch, generation) {
  const r = recipe();
  const step = VIEWPORT.step(view);
  const [x0, y0] = VIEWPORT.imageAt(view, 0, 0), [x1, y1] = VIEWPORT.imageAt(view, cw - 1, ch - 1);
  const needsRange = !["colour", "normal", "mask", "id"].includes(r.kind);
  const layerStats = stats(r.planes[0].which, state.selected);
  const [, range] = await Promise.all([needTiles(r, step, x0, y0, x1, y1),
    needsRange ? layerStats.then((s) => rangeOf(s, state.compare)) : [0, 1]]);
  if (generation !== null && generation !== state.generation) return null;
  const { width, height } = state.meta;
  const img = new ImageData(cw, ch);
  const out = img.data, px = new Float64Array(8), paint = painter(r, range);
  for (let cy = 0; cy < ch; cy++) {
    const y = Math.floor(view.y + (cy + 0.5) / view.zoom);
    for (let cx = 0; cx < cw; cx++) {
      const x = Math.floor(view.x + (cx + 0.5) / view.zoom);
      const o = (cy * cw + cx) * 4;
      out[o + 3] = 255;
      if (x < 0 || y < 0 || x >= width || y >= height || !gather(r, x, y, step, px)) {
        out[o] = out[o + 1] = out[o + 2] = 21;
        continue;
      }
      paint(px, out, o);
    }
  }
  return { img, r, range, step };
}

/** Shows what went wrong where the status is; the page goes on working. */
function fail(e) {
  $("status").textContent = `error: ${e.message}`;
  $("status").className = "problem";
}

/** Draws the current view; a draw overtaken by a newer one while it waited is dropped. A
 * draw that fails (a layer the server cannot send) says so and leaves the page working. */
function draw() {
  return drawNow().catch(fail);
}

async function drawNow() {
  const generation = ++state.generation;
  const stage = $("stage"), canvas = $("canvas");
  const cw = Math.max(1, stage.clientWidth), ch = Math.max(1, stage.clientHeight);
  if (state.fitted) VIEWPORT.fit(state.view, cw, ch, state.meta.width, state.meta.height);
  const done = await render(state.view, cw, ch, generation);
  if (!done) return;
  canvas.width = cw;
  canvas.height = ch;
  const ctx = canvas.getContext("2d");
  ctx.putImageData(done.img, 0, 0);
  if (state.view.zoom >= VALUE_ZOOM) writeValues(ctx, done.r, cw, ch);
  const scaled = done.r.kind === "metric" || done.r.kind === "false";
  PANELS.scaleBar($("scale"), scaled ? done.r.map : null, done.range[0], done.range[1],
    isMetric(state.compare) ? `${state.compare.replaceAll("-", " ")} of ${state.selected} (mean of the channels)` : state.selected);
  showStatus();
  showStatistics();
}

/** Each visible pixel's values, written inside it (the pixels are large enough). */
function writeValues(ctx, r, cw, ch) {
  const view = state.view, px = new Float64Array(8), n = r.planes[0].picks.length;
  const [x0, y0] = VIEWPORT.imageAt(view, 0, 0), [x1, y1] = VIEWPORT.imageAt(view, cw, ch);
  const size = Math.min(14, Math.floor(view.zoom / (n + 1)));
  ctx.font = `${size}px ui-monospace, monospace`;
  ctx.textAlign = "center";
  ctx.textBaseline = "middle";
  for (let y = Math.max(y0, 0); y <= Math.min(y1, state.meta.height - 1); y++) {
    for (let x = Math.max(x0, 0); x <= Math.min(x1, state.meta.width - 1); x++) {
      if (!gather(r, x, y, 1, px)) continue;
      const [cx, cy] = VIEWPORT.canvasAt(view, x, y);
      const [pr, pg, pb] = ctx.getImageData(Math.floor(cx), Math.floor(cy), 1, 1).data;
      ctx.fillStyle = 0.299 * pr + 0.587 * pg + 0.114 * pb > 128 ? "#000" : "#fff";
      for (let c = 0; c < n; c++) ctx.fillText(px[c].toPrecision(4), cx, cy + (c - (n - 1) / 2) * size * 1.15);
    }
  }
}

function showStatus(hover) {
  const op = $("tonemap").value, ev = Number($("exposure").value);
  const [image, reference] = state.meta.labels;
  const relit = state.selected === "beauty" && relighting() && state.compare === "a" ? " (relit)" : "";
  const shown = state.compare === "a" ? `${state.selected}${relit} of ${image}`
    : state.compare === "b" ? `${state.selected} of ${reference}`
    : `${state.compare.replaceAll("-", " ")} of ${state.selected}: ${image} against ${reference}`;
  let text = `${shown}, ${op}, EV ${ev.toFixed(1)}, zoom ${state.view.zoom >= 1 ? state.view.zoom.toFixed(2) : `1/${(1 / state.view.zoom).toFixed(2)}`}`;
  if (hover) text += `   (${hover[0]}, ${hover[1]}): ${hover[2]}`;
  if (state.meta.problem) text += `\nthe last reload failed: ${state.meta.problem}`;
  $("status").textContent = text;
  $("status").className = state.meta.problem ? "problem" : "";
}

async function showStatistics() {
  const which = whichOf(state.compare), name = state.selected;
  try {
    const s = await stats(which, name);
    if (which !== whichOf(state.compare) || name !== state.selected) return;
    PANELS.statistics($("stats"), `${name}${which === "main" ? "" : ` (${which})`}, every pixel`, s);
    $("differing").textContent = s.differing_pixels === null ? ""
      : `${s.differing_pixels} of ${state.meta.width * state.meta.height} pixels of ${name} differ from the reference`;
  } catch (e) {
    $("stats").textContent = e.message;
  }
}

/** Every pixel at full resolution as shown now (for `save PNG` and the tests). */
async function fullImage() {
  const { width, height } = state.meta;
  const done = await render({ zoom: 1, x: 0, y: 0 }, width, height, null);
  return done.img;
}

/** The values shown at image pixel (x, y) (the relit sum, or the metric), at full resolution. */
async function valueAt(x, y) {
  const r = recipe();
  await needTiles(r, 1, x, y, x, y);
  const px = new Float64Array(8);
  gather(r, x, y, 1, px);
  return Array.from(px.slice(0, r.planes[0].picks.length));
}

// ---- thumbnails ----
async function thumbnails() {
  const nav = $("layers");
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
  const figures = [];
  for (const [group, names] of Object.entries(groups)) {
    if (!names.length) continue;
    const h = document.createElement("h3");
    h.textContent = group;
    nav.append(h);
    for (const name of names) {
      const fig = document.createElement("figure");
      fig.dataset.layer = name;
      if (name === state.selected) fig.className = "selected";
      const c = Object.assign(document.createElement("canvas"), { width: Math.floor(width / step), height: Math.floor(height / step) });
      const cap = document.createElement("figcaption");
      cap.textContent = name;
      fig.append(c, cap);
      fig.onclick = () => select(name);
      nav.append(fig);
      figures.push([fig, c, name]);
    }
  }
  for (const [fig, c, name] of figures) {
    // One layer that cannot be had (a 404, a 503 under a tight memory limit) costs its
    // thumbnail only: the others, and the controls, go on working.
    try {
      const l = info(name), small = await wholeLayer(name, "main", step), n = l.channels.length;
      let lo = Infinity, hi = -Infinity;
      for (const x of small) if (Number.isFinite(x) && Math.abs(x) < 1e10) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
      const rgb = ["R", "G", "B"].map((ch) => l.channels.indexOf(ch));
      const picks = l.role === "colour" ? rgb : l.channels.map((_, i) => i);
      const paint = painter({ planes: [{ picks }], kind: l.role === "colour" ? "colour" : l.role }, [lo, hi > lo ? hi : lo + 1]);
      const img = new ImageData(c.width, c.height), px = new Float64Array(8);
      for (let q = 0; q < c.width * c.height; q++) {
        for (let k = 0; k < picks.length; k++) px[k] = small[q * n + picks[k]];
        paint(px, img.data, q * 4);
        img.data[q * 4 + 3] = 255;
      }
      c.getContext("2d").putImageData(img, 0, 0);
    } catch (e) {
      fig.title = e.message;
      fig.classList.add("unavailable");
    }
  }
}

function select(name) {
  if (!info(name)) return draw();
  state.selected = name;
  for (const f of document.querySelectorAll("nav figure")) f.classList.toggle("selected", f.dataset.layer === name);
  return draw();
}

// ---- probe and ray trees ----
async function probe(x, y) {
  const reply = await getJson(`/api/pixel?x=${x}&y=${y}`);
  const values = reply.values;
  const sum = [0, 0, 0];
  for (const [name, gain] of relightTerms()) {
    const v = values[name] || [0, 0, 0];
    for (let c = 0; c < 3; c++) sum[c] += v[c] * gain[c];
  }
  const text = [`pixel (${x}, ${y})`, `RGB = ambient + sum light + background = ${sum.map((v) => v.toPrecision(6)).join(", ")}`];
  for (const [name, v] of Object.entries(values)) {
    const ref = reply.reference && reply.reference[name];
    text.push(`${name}: ${v.map((e) => e.toPrecision(6)).join(", ")}${ref ? `   reference ${ref.map((e) => e.toPrecision(6)).join(", ")}` : ""}`);
  }
  $("probe").textContent = text.join("\n");
  return { pixel: [x, y], values, reference: reply.reference, breakdown: sum };
}

async function showTrees(x, y) {
  if (!state.meta.trees) return null;
  const reply = await getJson(`/api/trees?x=${x}&y=${y}`);
  state.trees = [x, y];
  TREES.show($("trees"), x, y, reply);
  return reply;
}

async function inspect(x, y) {
  const { width, height } = state.meta;
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  await Promise.all([probe(x, y), showTrees(x, y)]).catch(fail);
}

/** Inspects pixel (x, y) and centres the view on it at a zoom its values show at (after the
 * ray trees have opened below the image, so it is centred in what is left). */
async function goTo(x, y) {
  await inspect(x, y);
  const stage = $("stage");
  state.fitted = false;
  Object.assign(state.view, { zoom: VALUE_ZOOM, x: x + 0.5 - stage.clientWidth / (2 * VALUE_ZOOM), y: y + 0.5 - stage.clientHeight / (2 * VALUE_ZOOM) });
  return draw();
}

// ---- relight panel ----
function hexToGain(hex, scale) {
  return [1, 3, 5].map((i) => (parseInt(hex.slice(i, i + 2), 16) / 255) * scale);
}
function relightPanel() {
  const panel = $("relight");
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

// ---- controls ----
function setExposure(ev) {
  const e = Math.min(8, Math.max(-8, ev));
  $("exposure").value = e;
  $("exposure-value").textContent = e.toFixed(1);
  return draw();
}
function setCompare(mode) {
  if (!state.meta.reference) mode = "a";
  state.compare = mode;
  $("compare").value = mode;
  return draw();
}
function fit() { state.fitted = true; return draw(); }
function actualSize() {
  state.fitted = false;
  VIEWPORT.actual(state.view, $("stage").clientWidth, $("stage").clientHeight);
  return draw();
}
function zoomAt(cx, cy, factor) {
  state.fitted = false;
  VIEWPORT.zoomAt(state.view, cx, cy, factor);
  return draw();
}
function reset() {
  Object.assign(state, { gains: {}, shadows: {}, ambient: 1, background: 1 });
  $("tonemap").value = "tick";
  relightPanel();
  state.fitted = true;
  return setExposure(0);
}
function stepLayer(by) {
  const names = [...document.querySelectorAll("nav figure")].map((f) => f.dataset.layer);
  const i = names.indexOf(state.selected);
  return select(names[(i + by + names.length) % names.length]);
}
function toggleHelp(show = $("help").hidden) { $("help").hidden = !show; }

const KEYS = {
  "?": () => toggleHelp(),
  e: () => setExposure(Number($("exposure").value) + 0.5),
  E: () => setExposure(Number($("exposure").value) - 0.5),
  "]": () => stepLayer(1), ArrowDown: () => stepLayer(1),
  "[": () => stepLayer(-1), ArrowUp: () => stepLayer(-1),
  b: () => setCompare(state.compare === "a" ? "b" : "a"),
  m: () => {
    const modes = [...$("compare").options].map((o) => o.value);
    return setCompare(modes[(modes.indexOf(state.compare) + 1) % modes.length]);
  },
  f: fit,
  1: actualSize,
  "+": () => zoomAt($("stage").clientWidth / 2, $("stage").clientHeight / 2, 2),
  "=": () => zoomAt($("stage").clientWidth / 2, $("stage").clientHeight / 2, 2),
  "-": () => zoomAt($("stage").clientWidth / 2, $("stage").clientHeight / 2, 0.5),
  r: reset,
  Escape: () => { toggleHelp(false); $("trees").hidden = true; },
};

function wireControls() {
  for (const op of TONEMAP.names) $("tonemap").append(new Option(op, op));
  for (const map of COLORMAP.names) $("colormap").append(new Option(map, map));
  const compare = $("compare");
  compare.append(new Option("the image", "a"), new Option("the reference", "b"));
  for (const m of state.meta.metrics) compare.append(new Option(m.replaceAll("-", " "), m));
  $("compare-label").hidden = !state.meta.reference;
  compare.value = state.compare;
  compare.onchange = () => setCompare(compare.value);
  $("tonemap").onchange = draw;
  $("colormap").onchange = draw;
  $("exposure").oninput = (e) => setExposure(Number(e.target.value));
  $("fit").onclick = fit;
  $("actual").onclick = actualSize;
  $("help-button").onclick = () => toggleHelp();
  $("help").onclick = () => toggleHelp(false);
  const table = $("shortcuts");
  for (const [keys, what] of SHORTCUTS) {
    const tr = document.createElement("tr");
    for (const t of [keys, what]) { const td = document.createElement("td"); td.textContent = t; tr.append(td); }
    table.append(tr);
  }
  document.addEventListener("keydown", (e) => {
    if (e.target.tagName === "INPUT" || e.target.tagName === "SELECT" || e.ctrlKey || e.metaKey || e.altKey) return;
    const action = KEYS[e.key];
    if (action) { e.preventDefault(); action(); }
  });
  const canvas = $("canvas");
  const local = (e) => { const r = canvas.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; };
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const [cx, cy] = local(e);
    zoomAt(cx, cy, Math.pow(2, -e.deltaY / 300));
  }, { passive: false });
  let drag = null;
  canvas.addEventListener("mousedown", (e) => { drag = { at: local(e), moved: 0 }; });
  window.addEventListener("mousemove", (e) => {
    const [cx, cy] = local(e);
    if (drag) {
      const dx = cx - drag.at[0], dy = cy - drag.at[1];
      drag.moved += Math.abs(dx) + Math.abs(dy);
      drag.at = [cx, cy];
      if (drag.moved > 3) { state.fitted = false; VIEWPORT.pan(state.view, dx, dy); draw(); }
      return;
    }
    if (e.target !== canvas) return;
    const [x, y] = VIEWPORT.imageAt(state.view, cx, cy), r = recipe(), px = new Float64Array(8);
    if (x >= 0 && y >= 0 && x < state.meta.width && y < state.meta.height && gather(r, x, y, VIEWPORT.step(state.view), px))
      showStatus([x, y, Array.from(px.slice(0, r.planes[0].picks.length), (v) => v.toPrecision(5)).join(", ")]);
  });
  window.addEventListener("mouseup", (e) => {
    const click = drag && drag.moved <= 3 && e.target === canvas;
    drag = null;
    if (click) { const [x, y] = VIEWPORT.imageAt(state.view, ...local(e)); inspect(x, y); }
  });
  // The stage changes size with the window, and when the ray trees open below it.
  let size = "";
  new ResizeObserver(() => {
    const now = `${$("stage").clientWidth}x${$("stage").clientHeight}`;
    if (now !== size) { size = now; if (state.meta) draw(); }
  }).observe($("stage"));
  $("reset").onclick = reset;
  $("save").onclick = async () => {
    const img = await fullImage();
    const c = Object.assign(document.createElement("canvas"), { width: img.width, height: img.height });
    c.getContext("2d").putImageData(img, 0, 0);
    c.toBlob((blob) => {
      const a = Object.assign(document.createElement("a"), { href: URL.createObjectURL(blob), download: `${state.selected}.png` });
      a.click();
    });
  };
}

// ---- loading, and --watch ----
async function load() {
  state.meta = await getJson("/api/image");
  state.version = state.meta.version;
  TILES.size = state.meta.tile;
  if (!info(state.selected)) state.selected = state.meta.layers[0].name;
  if (state.meta.check) {
    $("check-panel").hidden = false;
    PANELS.check($("check"), await getJson("/api/check"), goTo);
  }
}

/** Follows reloads (`--watch`): a new version drops everything fetched and draws again. */
async function follow() {
  for (;;) {
    await new Promise((resolve) => setTimeout(resolve, 500));
    try {
      const v = await getJson("/api/version");
      if (v.version !== state.version) {
        TILES.clear();
        state.stats = new Map();
        await load();
        await draw();
        thumbnails();
        if (state.trees) showTrees(...state.trees).catch(() => {});
        window.whitted.reloads++;
      } else if (v.problem !== state.meta.problem) {
        state.meta.problem = v.problem;
        showStatus();
      }
    } catch (e) {
      $("status").textContent = `the viewer is not answering: ${e.message}`;
    }
  }
}

async function start() {
  await load();
  // A check opens on where the image differs, in false colour.
  if (state.meta.check) state.compare = "absolute-error";
  // The controls are wired first: a layer that fails to load below leaves them working.
  wireControls();
  relightPanel();
  state.fitted = true;
  await draw();
  window.whitted.ready = true;
  await thumbnails();
  window.whitted.thumbnails = true;
  follow();
}

// What the browser tests (and a curious user's console) drive: the same functions the
// controls call.
window.whitted = {
  ready: false,
  errors: [], // every uncaught error and unhandled rejection, which the browser tests read

  thumbnails: false,
  reloads: 0,
  probe,
  select,
  showTrees,
  goTo,
  valueAt,
  setCompare,
  setExposure,
  zoomAt,
  fit,
  view: () => ({ ...state.view }),
  imageAt: (cx, cy) => VIEWPORT.imageAt(state.view, cx, cy),
  canvasAt: (x, y) => VIEWPORT.canvasAt(state.view, x, y),
  setGain(light, r, g, b) { state.gains[light] = [r, g, b]; return draw(); },
  setShadows(light, on) { state.shadows[light] = on; return draw(); },
  setToneMap(op, ev) { $("tonemap").value = op; return setExposure(ev); },
  setColormap(map) { $("colormap").value = map; return draw(); },
  async pixels() { const img = await fullImage(); state.display = img.data; return Array.from(img.data); },
};
window.addEventListener("error", (e) => window.whitted.errors.push(e.message));
window.addEventListener("unhandledrejection", (e) => window.whitted.errors.push(String(e.reason)));
start().catch(fail);
