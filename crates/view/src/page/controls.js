// ---- the controls: the relight panel, the header, the keyboard, the mouse ----
"use strict";

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
    const div = row(`light ${light}`, 1, (g, colour) => { state.gains.set(light, hexToGain(colour, g)); draw(); }, true);
    const box = Object.assign(document.createElement("input"), { type: "checkbox", checked: true });
    box.onchange = () => { state.shadows.set(light, box.checked); draw(); };
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
  VIEWPORT.actual(state.view, ...VIEWPORT.canvasSize($("stage")));
  return draw();
}
function zoomAt(cx, cy, factor) {
  state.fitted = false;
  VIEWPORT.zoomAt(state.view, cx, cy, factor);
  return draw();
}
function zoomAtCentre(factor) {
  const [cw, ch] = VIEWPORT.canvasSize($("stage"));
  return zoomAt(cw / 2, ch / 2, factor);
}
function reset() {
  Object.assign(state, { gains: new Map(), shadows: new Map(), ambient: 1, background: 1 });
  // The course year's own PNG: `sigmoid` for a later year's EXR (`render/course`).
  $("tonemap").value = state.meta.tonemap || "tick";
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
  "+": () => zoomAtCentre(2),
  "=": () => zoomAtCentre(2),
  "-": () => zoomAtCentre(0.5),
  r: reset,
  Escape: () => { toggleHelp(false); $("trees").hidden = true; },
};

function wireControls() {
  for (const op of TONEMAP.names) $("tonemap").append(new Option(op, op));
  $("tonemap").value = state.meta.tonemap || "tick";
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
  const local = (e) => VIEWPORT.local(canvas, e);
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
  // The stage changes size with the window, and when the ray trees open below it; the
  // pixel ratio changes when the window moves to another screen (or the page is zoomed).
  let size = "";
  const resized = () => {
    const now = VIEWPORT.canvasSize($("stage")).join("x");
    if (now !== size) { size = now; if (state.meta) draw(); }
  };
  new ResizeObserver(resized).observe($("stage"));
  const followRatio = () => {
    matchMedia(`(resolution: ${VIEWPORT.ratio()}dppx)`).addEventListener("change", () => { resized(); followRatio(); }, { once: true });
  };
  followRatio();
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

