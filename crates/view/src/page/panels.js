// ---- panels: statistics and histogram, the false-colour scale bar, the check's report,
// the shortcuts overlay ----
"use strict";

const PANELS = (() => {
  const number = (x) => (x === null || x === undefined ? "-" : Number(x).toPrecision(5));
  const CHANNEL_COLOURS = ["#e55", "#5c5", "#59f", "#bbb"];
  return {
    /** The statistics of `stats` (/api/stats) and its histogram, into `element`. */
    statistics(element, title, stats) {
      element.textContent = "";
      const caption = document.createElement("p");
      caption.textContent = title;
      const table = document.createElement("table");
      table.className = "stats";
      const head = document.createElement("tr");
      for (const h of ["", "min", "max", "mean", "NaN", "Inf"]) {
        const th = document.createElement("th");
        th.textContent = h;
        head.append(th);
      }
      table.append(head);
      for (const c of stats.channels) {
        const tr = document.createElement("tr");
        for (const cell of [c.name, number(c.min), number(c.max), number(c.mean), c.nan, c.inf]) {
          const td = document.createElement("td");
          td.textContent = cell;
          tr.append(td);
        }
        table.append(tr);
      }
      // 256 x 80 CSS pixels (style.css), drawn at the screen's own resolution.
      const [w, h, ratio] = [256, 80, VIEWPORT.ratio()];
      const canvas = Object.assign(document.createElement("canvas"), { width: Math.round(w * ratio), height: Math.round(h * ratio), className: "histogram" });
      const ctx = canvas.getContext("2d");
      ctx.scale(canvas.width / w, canvas.height / h);
      const bins = stats.histogram.bins;
      const peak = Math.max(1, ...bins.flat());
      bins.forEach((counts, c) => {
        ctx.strokeStyle = CHANNEL_COLOURS[Math.min(c, 3)];
        ctx.beginPath();
        counts.forEach((n, i) => {
          const x = (i + 0.5) * (w / counts.length);
          // Square-root counts, so a few outliers still show beside a large flat area.
          const y = h - 2 - (h - 4) * Math.sqrt(n / peak);
          if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
        });
        ctx.stroke();
      });
      const range = document.createElement("p");
      range.className = "range";
      range.textContent = `histogram over ${number(stats.histogram.lo)} .. ${number(stats.histogram.hi)}`;
      element.append(caption, table, canvas, range);
    },
    /** The scale bar of colour map `map` over [lo, hi]; hidden when `map` is null. */
    scaleBar(element, map, lo, hi, label) {
      element.hidden = !map;
      if (!map) return;
      element.textContent = "";
      const canvas = Object.assign(document.createElement("canvas"), { width: 256, height: 12 });
      const ctx = canvas.getContext("2d");
      const img = ctx.createImageData(256, 12);
      for (let x = 0; x < 256; x++) {
        for (let y = 0; y < 12; y++) {
          COLORMAP.into(lo + ((hi - lo) * x) / 255, lo, hi, map, img.data, (y * 256 + x) * 4);
          img.data[(y * 256 + x) * 4 + 3] = 255;
        }
      }
      ctx.putImageData(img, 0, 0);
      const labels = document.createElement("div");
      labels.className = "labels";
      for (const t of [number(lo), label, number(hi)]) {
        const span = document.createElement("span");
        span.textContent = t;
        labels.append(span);
      }
      element.append(canvas, labels);
    },
    /** The check's report (/api/check) into `element`; `goTo(x, y)` shows a pixel. */
    check(element, report, goTo) {
      element.textContent = "";
      const line = (text, className) => {
        const p = document.createElement("p");
        p.textContent = text;
        if (className) p.className = className;
        element.append(p);
        return p;
      };
      line(`${report.scene}, ${report.width}x${report.height}, ${report.bounces} bounces: ${report.verdict_text || report.verdict}`, `verdict ${report.verdict}`);
      line(report.difference_text);
      // The server's words (the check's words.rs), the same as the text report's.
      if (report.hidden_text) line(report.hidden_text);
      for (const text of report.summary || []) line(text, "summary");
      if (report.worst_pixel) {
        const [x, y] = report.worst_pixel;
        const button = Object.assign(document.createElement("button"), { textContent: `worst pixel (${x}, ${y})` });
        button.onclick = () => goTo(x, y);
        element.append(button);
      }
      if (report.diagnosis.length) {
        line(report.diagnosis_heading || "diagnosis, best first:");
        const list = document.createElement("ol");
        list.className = "diagnosis";
        for (const d of report.diagnosis) {
          const li = document.createElement("li");
          // The server's words, the same as the text report's.
          li.textContent = d.text.join("\n ");
          list.append(li);
        }
        element.append(list);
      } else if (report.differing_pixels > 0) {
        line("no catalogued mistake reproduces the image better than the reference does");
      }
      line("click a pixel for its ray trees");
    },
  };
})();

/** The keyboard shortcuts, as the `?` overlay lists them and the page handles them. */
const SHORTCUTS = [
  ["?", "show or hide this list"],
  ["e / E", "exposure up / down half a stop"],
  ["] or Down / [ or Up", "next / previous layer"],
  ["b", "flip between the image and the reference (A/B)"],
  ["m", "next comparison: image, reference, then each error metric"],
  ["f", "fit the image to the window"],
  ["1", "one image pixel per screen pixel (1:1)"],
  ["+ / -", "zoom in / out about the centre"],
  ["wheel, drag", "zoom about the cursor, pan"],
  ["r", "reset: exposure 0, the tone map, relighting, fit"],
  ["Escape", "close this list or the ray trees"],
];
