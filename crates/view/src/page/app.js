// ---- whitted view: drawing, thumbnails, the probe and ray trees, loading and --watch ----
// The page's other files, in the order they are sent: tonemap.js (the CLI's operators, same
// numbers), colormap.js (false colour), viewport.js (zoom, pan, the tile cache), panels.js
// (statistics, scale bar, check report, shortcuts), trees.js (ray trees), state.js (the state
// and its fetches), pixels.js (what a pixel shows), controls.js (relight panel, keys, mouse).
"use strict";

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
  if (e instanceof Stale) return; // the reload it started draws again
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
  const canvas = $("canvas"), [cw, ch] = VIEWPORT.canvasSize($("stage"));
  if (state.fitted) VIEWPORT.fit(state.view, cw, ch, state.meta.width, state.meta.height);
  const done = await render(state.view, cw, ch, generation);
  if (!done) return;
  canvas.width = cw;
  canvas.height = ch;
  canvas.style.width = `${cw / VIEWPORT.ratio()}px`;
  canvas.style.height = `${ch / VIEWPORT.ratio()}px`;
  const ctx = canvas.getContext("2d");
  ctx.putImageData(done.img, 0, 0);
  if (state.view.zoom >= valueZoom()) writeValues(ctx, done.r, cw, ch);
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
  const size = Math.min(14 * VIEWPORT.ratio(), Math.floor(view.zoom / (n + 1)));
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
    // The server knows which group a layer name is in (aov.rs): no prefixes re-derived here.
    (groups[l.group] || groups.data).push(l.name);
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
      const c = Object.assign(document.createElement("canvas"), { width: Math.ceil(width / step), height: Math.ceil(height / step) });
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
      for (const x of small) if (shownInRange(x)) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
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
  // Layer names come from the file: looked up in maps, never as an object's properties.
  const values = new Map(Object.entries(reply.values));
  const references = new Map(Object.entries(reply.reference || {}));
  // JSON has no NaN or infinities: the server sends null for them.
  const value = (e) => (e === null ? NaN : e);
  const show = (v) => v.map((e) => (e === null ? "non-finite" : e.toPrecision(6))).join(", ");
  const sum = [0, 0, 0];
  for (const [name, gain] of relightTerms()) {
    const v = values.get(name) || [0, 0, 0];
    for (let c = 0; c < 3; c++) sum[c] += value(v[c]) * gain[c];
  }
  const text = [`pixel (${x}, ${y})`, `RGB = ambient + sum light + background = ${sum.map((v) => (Number.isFinite(v) ? v.toPrecision(6) : "non-finite")).join(", ")}`];
  for (const [name, v] of values) {
    const ref = references.get(name);
    text.push(`${name}: ${show(v)}${ref ? `   reference ${show(ref)}` : ""}`);
  }
  $("probe").textContent = text.join("\n");
  return { pixel: [x, y], values: reply.values, reference: reply.reference, breakdown: sum };
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
  const [cw, ch] = VIEWPORT.canvasSize($("stage")), zoom = valueZoom();
  state.fitted = false;
  Object.assign(state.view, { zoom, x: x + 0.5 - cw / (2 * zoom), y: y + 0.5 - ch / (2 * zoom) });
  return draw();
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

/** Drops everything fetched, reads the image's description again and draws: after a reload
 * of the files, seen by `follow` or by a layer of a newer version (one reload at a time). */
let reloading = null;
function reload() {
  reloading ??= (async () => {
    TILES.clear();
    state.stats = new Map();
    await load();
    await draw();
    thumbnails();
    if (state.trees) showTrees(...state.trees).catch(() => {});
    window.whitted.reloads++;
  })().finally(() => { reloading = null; });
  return reloading;
}
reloadSoon = () => { reload().catch(fail); };

/** Follows reloads (`--watch` only: without it the files are read once). */
async function follow() {
  for (;;) {
    await sleep(500);
    try {
      const v = await getJson("/api/version");
      if (v.version !== state.version) {
        await reload();
      } else if (v.problem !== state.meta.problem) {
        state.meta.problem = v.problem;
        showStatus();
      }
    } catch (e) {
      $("status").textContent = `the viewer is not answering: ${e.message}`;
    }
  }
}

/** While the server's first load runs (a large EXR takes seconds), says what it reads. A
 * file that turns out unreadable stops the viewer, with the reason on its terminal. */
async function opened() {
  let reading = null;
  for (;;) {
    let v;
    try {
      v = await getJson("/api/version");
    } catch (e) {
      throw reading ? new Error(`the viewer stopped while reading ${reading} (its terminal says why)`) : e;
    }
    if (v.open) return;
    reading = v.reading;
    $("status").textContent = `reading ${v.reading}: ${Math.floor(v.seconds)} s so far`;
    await sleep(250);
  }
}

async function start() {
  await opened();
  await load();
  // Known before the page says it is ready: the reloads are followed once the first draw is done.
  window.whitted.following = state.meta.watching;
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
  if (state.meta.watching) follow();
}

// What the browser tests (and a curious user's console) drive: the same functions the
// controls call.
window.whitted = {
  ready: false,
  errors: [], // every uncaught error and unhandled rejection, which the browser tests read

  thumbnails: false,
  reloads: 0,
  following: false, // whether the page polls for reloads (with --watch only)
  probe,
  select,
  showTrees,
  goTo,
  valueAt,
  setCompare,
  setExposure,
  zoomAt,
  fit,
  actualSize,
  view: () => ({ ...state.view }),
  imageAt: (cx, cy) => VIEWPORT.imageAt(state.view, cx, cy),
  canvasAt: (x, y) => VIEWPORT.canvasAt(state.view, x, y),
  setGain(light, r, g, b) { state.gains.set(light, [r, g, b]); return draw(); },
  setShadows(light, on) { state.shadows.set(light, on); return draw(); },
  setToneMap(op, ev) { $("tonemap").value = op; return setExposure(ev); },
  setColormap(map) { $("colormap").value = map; return draw(); },
  async pixels() { const img = await fullImage(); state.display = img.data; return Array.from(img.data); },
};
window.addEventListener("error", (e) => window.whitted.errors.push(e.message));
window.addEventListener("unhandledrejection", (e) => window.whitted.errors.push(String(e.reason)));
start().catch(fail);
