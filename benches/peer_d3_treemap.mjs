// d3-hierarchy peer of `cargo bench --bench treemap`: a squarified treemap of 1,000,000 leaves in
// 3 levels (100 x 100 x 100 under one root), values uniform in (1, 100) from a fixed-seed xorshift,
// in a 1000x1000 box. Timed: d3.hierarchy(...).sum().sort() + d3.treemap() (squarify), best of 3.
// The nested input objects are built before timing (dataink's timing starts from a parent list).
// Usage: (cd benches && npm install --no-save d3-hierarchy && node peer_d3_treemap.mjs)
import { hierarchy, treemap, treemapSquarify } from "d3-hierarchy";

// xorshift64 as in benches/common (uniform in [0, 1)); BigInt for the 64-bit state.
function uniform(seed) {
  let state = BigInt(seed) || 1n;
  const mask = (1n << 64n) - 1n;
  return () => {
    state ^= (state << 13n) & mask;
    state ^= state >> 7n;
    state ^= (state << 17n) & mask;
    return Number(state >> 11n) / 2 ** 53;
  };
}

const rng = uniform(42);
const fanout = 100;
const root = { children: [] };
for (let i = 0; i < fanout; i++) {
  const a = { children: [] };
  for (let j = 0; j < fanout; j++) {
    const b = { children: [] };
    for (let k = 0; k < fanout; k++) b.children.push({ value: 1 + 99 * rng() });
    a.children.push(b);
  }
  root.children.push(a);
}

let best = Infinity;
let layoutRoot;
for (let run = 0; run < 3; run++) {
  const start = performance.now();
  const h = hierarchy(root)
    .sum((d) => d.value)
    .sort((a, b) => b.value - a.value);
  layoutRoot = treemap().tile(treemapSquarify).size([1000, 1000])(h);
  best = Math.min(best, performance.now() - start);
}
let leaves = 0;
let area = 0;
let aspect = 0;
for (const leaf of layoutRoot.leaves()) {
  const w = leaf.x1 - leaf.x0;
  const h = leaf.y1 - leaf.y0;
  leaves++;
  area += w * h;
  aspect += Math.max(w / h, h / w);
}
console.log(`d3-hierarchy treemap (squarify), ${leaves} leaves, 100x100x100: best of 3 = ${(best / 1000).toFixed(3)} s`);
console.log(`check: leaf area sum ${area.toFixed(3)}, mean leaf aspect ${(aspect / leaves).toFixed(10)}`);
