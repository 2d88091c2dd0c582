// d3-delaunay peer of `cargo bench --bench delaunay`: 1,000,000 uniformly random points.
// Usage: (cd benches && npm install --no-save d3-contour d3-delaunay && node peer_d3_delaunay.mjs)
import { Delaunay } from "d3-delaunay";

const n = 1_000_000;
const coords = new Float64Array(2 * n);
for (let i = 0; i < 2 * n; i++) coords[i] = Math.random();
let best = Infinity;
for (let run = 0; run < 3; run++) {
  const start = performance.now();
  const d = new Delaunay(coords);
  best = Math.min(best, performance.now() - start);
  if (d.triangles.length === 0) throw new Error("no triangles");
}
console.log(`d3-delaunay, 1e6 random points: best of 3 = ${(best / 1000).toFixed(3)} s`);
