//! A brute-force reference for one cell: the trilinear function sampled on a fine lattice, and
//! the components and Euler characteristics of `{g ≥ 0}` and `{g < 0}` found by flood fill and
//! by counting the cubical complex — nothing shared with the code under test.

/// The trilinear function with corner values `g` (corner `x | y << 1 | z << 2`).
pub fn trilinear(g: &[f64; 8], p: [f64; 3]) -> f64 {
    let mut sum = 0.0;
    for (c, v) in g.iter().enumerate() {
        let w: f64 = (0..3).map(|a| if c >> a & 1 == 1 { p[a] } else { 1.0 - p[a] }).product();
        sum += w * v;
    }
    sum
}

/// What the fine lattice says about one cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Components of `{g ≥ 0}` in the cell.
    pub inside: usize,
    /// Components of `{g < 0}` in the cell.
    pub outside: usize,
    /// Components of the surface in the cell: `inside + outside − 1` (the cell, a ball, cut by
    /// a properly embedded surface of `c` pieces falls into `c + 1` regions).
    pub surface: usize,
    /// Boundary loops of the surface: the pieces of the cube's surface minus one.
    pub loops: usize,
    /// The Euler characteristic of the surface, `χ(in) + χ(out) − χ(ball)`.
    pub euler: i64,
}

/// Components of the lattice points where `keep` holds, 6-connected, among points where
/// `allowed` holds.
fn flood(n: usize, keep: &[bool], allowed: &dyn Fn(usize, usize, usize) -> bool) -> usize {
    let m = n + 1;
    let idx = |i: usize, j: usize, k: usize| (k * m + j) * m + i;
    let mut seen = vec![false; keep.len()];
    let mut count = 0;
    let mut stack = Vec::new();
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let s = idx(i, j, k);
                if seen[s] || !keep[s] || !allowed(i, j, k) {
                    continue;
                }
                count += 1;
                seen[s] = true;
                stack.push((i, j, k));
                while let Some((i, j, k)) = stack.pop() {
                    let mut go = |a: usize, b: usize, c: usize| {
                        let t = idx(a, b, c);
                        if !seen[t] && keep[t] && allowed(a, b, c) {
                            seen[t] = true;
                            stack.push((a, b, c));
                        }
                    };
                    if i > 0 {
                        go(i - 1, j, k);
                    }
                    if i < n {
                        go(i + 1, j, k);
                    }
                    if j > 0 {
                        go(i, j - 1, k);
                    }
                    if j < n {
                        go(i, j + 1, k);
                    }
                    if k > 0 {
                        go(i, j, k - 1);
                    }
                    if k < n {
                        go(i, j, k + 1);
                    }
                }
            }
        }
    }
    count
}

/// The Euler characteristic of the cubical complex whose vertices are the kept lattice points
/// (an edge, square or cube is in it when all its corners are).
fn euler(n: usize, keep: &[bool]) -> i64 {
    let m = n + 1;
    let at = |i: usize, j: usize, k: usize| keep[(k * m + j) * m + i];
    let mut chi = 0i64;
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                if !at(i, j, k) {
                    continue;
                }
                chi += 1;
                let (x, y, z) = (i < n, j < n, k < n);
                // Edges, squares and the cube with this point as their lowest corner.
                if x && at(i + 1, j, k) {
                    chi -= 1;
                }
                if y && at(i, j + 1, k) {
                    chi -= 1;
                }
                if z && at(i, j, k + 1) {
                    chi -= 1;
                }
                let sq = |a: bool, b: bool, c: bool, d: bool| a && b && c && d;
                if x && y && sq(true, at(i + 1, j, k), at(i, j + 1, k), at(i + 1, j + 1, k)) {
                    chi += 1;
                }
                if x && z && sq(true, at(i + 1, j, k), at(i, j, k + 1), at(i + 1, j, k + 1)) {
                    chi += 1;
                }
                if y && z && sq(true, at(i, j + 1, k), at(i, j, k + 1), at(i, j + 1, k + 1)) {
                    chi += 1;
                }
                if x && y && z && (0..8).all(|c| at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1))) {
                    chi -= 1;
                }
            }
        }
    }
    chi
}

/// The topology of the cell with corner values `g` (level 0) on an `n`-step lattice.
pub fn topology(g: &[f64; 8], n: usize) -> Topology {
    let m = n + 1;
    let mut values = Vec::with_capacity(m * m * m);
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                values.push(trilinear(g, [i, j, k].map(|v| v as f64 / n as f64)));
            }
        }
    }
    let inside: Vec<bool> = values.iter().map(|v| *v >= 0.0).collect();
    let outside: Vec<bool> = inside.iter().map(|b| !b).collect();
    let anywhere = |_: usize, _: usize, _: usize| true;
    let on_surface = |i: usize, j: usize, k: usize| [i, j, k].iter().any(|&v| v == 0 || v == n);
    let (cin, cout) = (flood(n, &inside, &anywhere), flood(n, &outside, &anywhere));
    let patches = flood(n, &inside, &on_surface) + flood(n, &outside, &on_surface);
    Topology {
        inside: cin,
        outside: cout,
        surface: (cin + cout).saturating_sub(1),
        loops: patches.saturating_sub(1),
        euler: euler(n, &inside) + euler(n, &outside) - 1,
    }
}

/// Values of the critical points of the trilinear function inside the cell (faces' saddles,
/// which matter for the face decisions, and the body's saddles, for the interior).
pub fn saddle_values(g: &[f64; 8]) -> Vec<f64> {
    let mut out = Vec::new();
    // Faces: bilinear g00 + (g10 − g00)u + (g01 − g00)v + D uv.
    for axis in 0..3 {
        let (u, v) = (1 << ((axis + 1) % 3), 1 << ((axis + 2) % 3));
        for side in 0..2 {
            let base = side << axis;
            let (g00, g10, g01, g11) = (g[base], g[base | u], g[base | v], g[base | u | v]);
            let d = g00 - g10 - g01 + g11;
            if d != 0.0 {
                let (su, sv) = ((g00 - g01) / d, (g00 - g10) / d);
                if su > 0.0 && su < 1.0 && sv > 0.0 && sv < 1.0 {
                    out.push((g00 * g11 - g10 * g01) / d);
                }
            }
        }
    }
    // Body: g = a + bx + cy + dz + e xy + f yz + h xz + k xyz.
    let b = g[1] - g[0];
    let c = g[2] - g[0];
    let d = g[4] - g[0];
    let e = g[3] - g[2] - g[1] + g[0];
    let f = g[6] - g[4] - g[2] + g[0];
    let h = g[5] - g[4] - g[1] + g[0];
    let k = g[7] - g[6] - g[5] - g[3] + g[4] + g[2] + g[1] - g[0];
    if k.abs() > 1e-12 {
        // g = k(x+α)(y+β)(z+γ) + p(x+α) + q(y+β) + r(z+γ) + s.
        let (alpha, beta, gamma) = (f / k, h / k, e / k);
        let (p, q, r) = (b - k * beta * gamma, c - k * alpha * gamma, d - k * alpha * beta);
        let s = trilinear(g, [-alpha, -beta, -gamma]);
        let w2 = -p * q * r / k;
        if w2 > 0.0 && p != 0.0 && q != 0.0 && r != 0.0 {
            for w in [w2.sqrt(), -w2.sqrt()] {
                let x = [-w / p - alpha, -w / q - beta, -w / r - gamma];
                if x.iter().all(|&t| t > 0.0 && t < 1.0) {
                    out.push(s - 2.0 * w);
                }
            }
        }
    }
    out
}

#[test]
fn the_reference_knows_a_tunnel_and_a_ball() {
    // One corner in: a quarter ball, disk surface.
    let mut g = [-1.0; 8];
    g[0] = 1.0;
    let t = topology(&g, 20);
    assert_eq!(t, Topology { inside: 1, outside: 1, surface: 1, loops: 1, euler: 1 });
    // Corners 0 and 7 in with a high centre: a tube, χ = 0.
    let mut g = [-0.2; 8];
    g[0] = 1.0;
    g[7] = 1.0;
    let t = topology(&g, 40);
    assert_eq!(t, Topology { inside: 1, outside: 1, surface: 1, loops: 2, euler: 0 });
    // The body saddles of that function: the value at the saddles is above 0 (the tube is
    // open) and the same by symmetry.
    let s = saddle_values(&g);
    assert!(s.iter().all(|v| *v > 0.0), "{s:?}");
}
