// ---- what a pixel shows: the planes summed into it (a layer, the relit beauty, a metric),
// the tiles they are read from, and how the sum is painted ----
"use strict";

const relighting = () =>
  state.ambient !== 1 || state.background !== 1 ||
  state.meta.lights.some((l) => (state.gains.get(l) || [1, 1, 1]).some((g) => g !== 1) || state.shadows.get(l) === false);

/** The layers and gains of the relit image, in the order of the sum: the file's own (one
 * written with `--aovs light_0,light_1` has no ambient or background to add). */
function relightTerms() {
  const terms = [["ambient", [state.ambient, state.ambient, state.ambient]]];
  for (const light of state.meta.lights) {
    const name = state.shadows.get(light) === false ? `unshadowed_${light}` : `light_${light}`;
    terms.push([name, state.gains.get(light) || [1, 1, 1]]);
  }
  terms.push(["background", [state.background, state.background, state.background]]);
  return terms.filter(([name]) => info(name));
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
        out[o + c] = shownInRange(x) ? Math.round(255 * TONEMAP.clamp01((x - lo) / (hi - lo))) : 0;
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

