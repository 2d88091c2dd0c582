// d3-contour peer of `cargo bench --bench contour` (filled bands): the same 2000x2000 field and
// levels. d3-contour returns filled MultiPolygons (each the region above a threshold).
// Usage: (cd benches && npm install --no-save d3-contour d3-delaunay && node peer_d3_contour.mjs)
import { contours } from "d3-contour";

const n = 2000;
const values = new Float64Array(n * n);
for (let j = 0; j < n; j++) {
  const y = -3 + (6 * j) / (n - 1);
  for (let i = 0; i < n; i++) {
    const x = -3 + (6 * i) / (n - 1);
    values[j * n + i] = Math.sin(1.7 * x) * Math.cos(1.3 * y) + 0.2 * (x * x - y * y) + 0.1 * x * y + 0.2;
  }
}
const levels = [-2, -1.5, -1, -0.5, 0, 0.5, 1, 1.5, 2, 2.5];
let best = Infinity;
for (let run = 0; run < 3; run++) {
  const start = performance.now();
  const result = contours().size([n, n]).thresholds(levels)(values);
  best = Math.min(best, performance.now() - start);
  if (result.length !== levels.length) throw new Error("unexpected output");
}
console.log(`d3-contour, 2000x2000, 10 levels: best of 3 = ${(best / 1000).toFixed(3)} s`);
