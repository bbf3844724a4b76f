// ---- the viewport: which image pixel each canvas pixel shows, and the tiles behind it ----
// A view is { zoom: canvas pixels per image pixel, x, y: the image point at the canvas's
// top-left corner }. Zooming about a point keeps the image point under it where it is.
// Canvas pixels are the screen's own (device) pixels: on a HiDPI screen the canvas holds
// devicePixelRatio times the stage's CSS pixels, so nothing is scaled by the browser and 1:1
// is one image pixel per screen pixel.
"use strict";

const VIEWPORT = (() => {
  const MIN_ZOOM = 1 / 256, MAX_ZOOM = 512;
  return {
    /** Screen pixels per CSS pixel. */
    ratio() { return window.devicePixelRatio || 1; },
    /** The canvas size, in screen pixels, that covers `stage`. */
    canvasSize(stage) {
      const r = this.ratio();
      return [Math.max(1, Math.round(stage.clientWidth * r)), Math.max(1, Math.round(stage.clientHeight * r))];
    },
    /** The canvas point (screen pixels) of a mouse event on `canvas`. */
    local(canvas, e) {
      const b = canvas.getBoundingClientRect();
      return [(e.clientX - b.left) * (canvas.width / b.width), (e.clientY - b.top) * (canvas.height / b.height)];
    },
    fit(view, cw, ch, width, height) {
      view.zoom = Math.min(cw / width, ch / height);
      view.x = (width - cw / view.zoom) / 2;
      view.y = (height - ch / view.zoom) / 2;
    },
    /** 1:1 (one image pixel per canvas pixel, exactly) about the canvas centre. */
    actual(view, cw, ch) { this.zoomTo(view, cw / 2, ch / 2, 1); },
    zoomAt(view, cx, cy, factor) { this.zoomTo(view, cx, cy, view.zoom * factor); },
    /** Zoom `zoom` (clamped), the image point under canvas point (cx, cy) staying there. */
    zoomTo(view, cx, cy, zoom) {
      const u = view.x + cx / view.zoom, v = view.y + cy / view.zoom;
      view.zoom = Math.min(Math.max(zoom, MIN_ZOOM), MAX_ZOOM);
      view.x = u - cx / view.zoom;
      view.y = v - cy / view.zoom;
    },
    pan(view, dx, dy) { view.x -= dx / view.zoom; view.y -= dy / view.zoom; },
    /** The image pixel under canvas point (cx, cy) (screen pixels from the canvas's corner). */
    imageAt(view, cx, cy) { return [Math.floor(view.x + cx / view.zoom), Math.floor(view.y + cy / view.zoom)]; },
    /** The canvas point at the centre of image pixel (x, y). */
    canvasAt(view, x, y) { return [(x + 0.5 - view.x) * view.zoom, (y + 0.5 - view.y) * view.zoom]; },
    /** Image pixels per sample the view needs: 1 from 1:1 up, else the power of two nearest
     * to the pixels one canvas pixel covers. */
    step(view) { return view.zoom >= 1 ? 1 : Math.pow(2, Math.round(Math.log2(1 / view.zoom))); },
  };
})();

/** Tiles of layer samples, fetched once (a tile being fetched is waited for, not fetched
 * again) and kept up to a memory bound, the least recently used dropped first. */
const TILES = (() => {
  const LIMIT = 768 * 1024 * 1024;
  let entries = new Map(), bytes = 0;
  const key = (which, name, step, tx, ty) => `${which}\u0000${name}\u0000${step}\u0000${tx}\u0000${ty}`;
  return {
    size: 256,
    clear() { entries = new Map(); bytes = 0; },
    /** The tile if it is here, else undefined. */
    peek(which, name, step, tx, ty) {
      const e = entries.get(key(which, name, step, tx, ty));
      return e && e.data;
    },
    get(which, name, step, tx, ty, fetchTile) {
      const k = key(which, name, step, tx, ty);
      const found = entries.get(k);
      if (found) { entries.delete(k); entries.set(k, found); return found.promise; }
      const entry = { data: undefined, promise: null };
      const cache = entries; // a tile that arrives after clear() belongs to no cache
      entry.promise = fetchTile(which, name, step, tx, ty).then((data) => {
        entry.data = data;
        if (cache !== entries) return data;
        bytes += data.byteLength;
        for (const [old, e] of entries) {
          if (bytes <= LIMIT) break;
          if (e.data && old !== k) { bytes -= e.data.byteLength; entries.delete(old); }
        }
        return data;
      }, (error) => { cache.delete(k); throw error; });
      entries.set(k, entry);
      return entry.promise;
    },
  };
})();
