// ---- the page's state and what it fetches ----
"use strict";

const token = new URLSearchParams(location.search).get("token");
const api = (path) => `${path}${path.includes("?") ? "&" : "?"}token=${token}`;
const $ = (id) => document.getElementById(id);
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** CSS pixels an image pixel must cover before its values are written in it (on a HiDPI
 * screen, that many times devicePixelRatio canvas pixels: the text needs the same room). */
const VALUE_ZOOM = 48;
const valueZoom = () => VALUE_ZOOM * VIEWPORT.ratio();
/** What a miss stores in Z (docs/aovs.md): values this large are left out of display ranges,
 * as the server's statistics leave them out. */
const SENTINEL = 1e10;
/** Whether x counts towards a display range. */
const shownInRange = (x) => Number.isFinite(x) && Math.abs(x) < SENTINEL;

const state = {
  meta: null,
  version: 0,
  selected: "beauty",
  compare: "a", // "a" the image, "b" the reference, or an error metric's name
  view: { zoom: 1, x: 0, y: 0 },
  fitted: false, // whether the view still follows the window (until the user zooms or pans)
  // Maps, not objects: a light's name comes from a file, and `constructor` or `__proto__`
  // would find the object's own machinery.
  gains: new Map(), // light -> [r, g, b]
  shadows: new Map(), // light -> false when shown without its shadows
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
/** A layer computed from another load of the files than the one the page shows (a reload
 * came in between): never drawn, and the page reloads instead (`reloadSoon`, set by app.js). */
class Stale extends Error {}
let reloadSoon = () => {};
async function layerFloats(q) {
  const response = await fetchOk(`/api/layer?${q}`);
  const version = Number(response.headers.get("X-Whitted-Version"));
  if (version !== state.version) {
    reloadSoon();
    throw new Stale(`a reload came in (version ${version}, the page shows ${state.version})`);
  }
  return new Float32Array(await response.arrayBuffer());
}
const fetchTile = (which, name, step, tx, ty) =>
  layerFloats(`name=${encodeURIComponent(name)}&which=${which}&step=${step}&tx=${tx}&ty=${ty}`);
const wholeLayer = (name, which, step) =>
  layerFloats(`name=${encodeURIComponent(name)}&which=${which}&step=${step}`);
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

