// ---- ray trees: one pixel as the reference traces it and as the top mistake does ----
// Each tree (the JSON of `whitted explain --json`) is flattened into rows with a key that
// names the term (depth, light, quantity); a row whose value differs from the other tree's
// row of the same key, or that the other tree lacks, is marked.
"use strict";

const TREES = (() => {
  const number = (x) => (x === null ? "non-finite" : Number(x).toPrecision(6));
  const vector = (v) => (v ? `(${v.map(number).join(", ")})` : "-");
  function rows(tree) {
    const out = [];
    const add = (key, label, value) => out.push({ key, label, value: JSON.stringify(value), text: typeof value === "string" ? value : Array.isArray(value) ? vector(value) : number(value) });
    add("camera", "camera ray", tree.camera_ray.direction);
    for (const v of tree.vertices) {
      const d = `depth ${v.depth}`;
      add(`${d}.hit`, `${d}: hits`, `object ${v.object} (${v.kind}) at s = ${number(v.distance)}`);
      add(`${d}.P`, "P", v.P);
      add(`${d}.N`, "N", v.N);
      add(`${d}.weight`, "weight w", v.weight);
      add(`${d}.ambient`, "ambient", v.ambient);
      for (const l of v.lights) {
        const k = `${d}.light ${l.light}`;
        add(`${k}.L`, `light ${l.light}: L`, l.L);
        add(`${k}.I`, "  I", l.I);
        add(`${k}.n_dot_l`, "  max(0, N.L)", l.n_dot_l);
        add(`${k}.r_dot_v`, "  max(0, R.V)", l.r_dot_v);
        add(`${k}.diffuse`, "  diffuse", l.diffuse);
        add(`${k}.specular`, "  specular", l.specular);
        const shadow = !l.shadow_tested ? "not tested: lit"
          : l.occluder ? `blocked by object ${l.occluder.object} (${l.occluder.kind})` : "reaches the light: lit";
        add(`${k}.shadow`, "  shadow ray", shadow);
      }
      add(`${d}.colour`, "shaded colour", v.colour);
    }
    if (tree.miss) add(`depth ${tree.miss.depth}.hit`, `depth ${tree.miss.depth}: misses`, "background");
    add("beauty", "beauty", tree.beauty_f64);
    return out;
  }
  function column(title, mine, theirs) {
    const section = document.createElement("div");
    section.className = "tree";
    const h = document.createElement("h3");
    h.textContent = title;
    section.append(h);
    const others = new Map(theirs ? theirs.map((r) => [r.key, r.value]) : []);
    const table = document.createElement("table");
    let differing = 0;
    for (const r of mine) {
      const tr = document.createElement("tr");
      const differs = theirs && others.get(r.key) !== r.value;
      if (differs) { tr.className = "differs"; differing++; }
      tr.dataset.key = r.key;
      for (const cell of [r.label, r.text]) {
        const td = document.createElement("td");
        td.textContent = cell;
        tr.append(td);
      }
      table.append(tr);
    }
    section.append(table);
    section.dataset.differing = differing;
    return section;
  }
  return {
    /** Shows pixel (x, y)'s trees (`reply` of /api/trees) in `element`. */
    show(element, x, y, reply) {
      element.textContent = "";
      const head = document.createElement("p");
      const reference = rows(reply.reference);
      const mistake = reply.mistake && rows(reply.mistake);
      head.textContent = `pixel (${x}, ${y})` + (mistake ? ": the rows that differ are marked" : "");
      element.append(head);
      const both = document.createElement("div");
      both.className = "trees";
      both.append(column("reference", reference, mistake));
      if (mistake) both.append(column(`top mistake: ${reply.mistake.bugs.join(" + ")}`, mistake, reference));
      element.append(both);
      element.hidden = false;
    },
    rows,
  };
})();
